// SPDX-License-Identifier: Apache-2.0
#include "components/magnetometer/MagnetometerModel.hpp"

#include <cmath>
#include <stdexcept>

namespace flatsat::magnetometer {

std::vector<std::string> MagnetometerParams::validate() const {
  std::vector<std::string> errors;
  // Written as !(x >= 0) so NaN is rejected too.
  if (!(noise_T >= 0.0) || !std::isfinite(noise_T)) {
    errors.emplace_back("noise_T: must be finite and >= 0");
  }
  if (!bias_B_T.allFinite()) {
    errors.emplace_back("bias_B_T: must be finite");
  }
  if (!scale_factor.allFinite() || !(scale_factor.minCoeff() > 0.0)) {
    errors.emplace_back("scale_factor: every axis must be finite and > 0");
  }
  if (!(quantum_T >= 0.0) || !std::isfinite(quantum_T)) {
    errors.emplace_back("quantum_T: must be finite and >= 0");
  }
  if (!(range_T > 0.0) || !std::isfinite(range_T)) {
    errors.emplace_back("range_T: must be finite and > 0");
  }
  return errors;
}

MagnetometerModel::MagnetometerModel(const Params& params) : params_(params), noise_(params.seed) {
  if (const auto errors = params_.validate(); !errors.empty()) {
    std::string message = "MagnetometerParams invalid:";
    for (const auto& e : errors) {
      message += " " + e + ";";
    }
    throw std::invalid_argument(message);
  }
}

void MagnetometerModel::reset() { noise_.reset(); }

MagnetometerOutput MagnetometerModel::step(const Input& in, std::int64_t /*t_ns*/) {
  Eigen::Vector3d b = params_.scale_factor.cwiseProduct(in.b_B_T) + params_.bias_B_T +
                      noise_.vector<3>(params_.noise_T);
  if (params_.quantum_T > 0.0) {
    b = (b / params_.quantum_T).array().round() * params_.quantum_T;
  }
  // Clip after quantising so the output never leaves ±range_T, like an ADC's end code.
  Output out;
  out.saturated = (b.array().abs() > params_.range_T).any();
  out.b_B_T = b.cwiseMax(-params_.range_T).cwiseMin(params_.range_T);
  return out;
}

}  // namespace flatsat::magnetometer
