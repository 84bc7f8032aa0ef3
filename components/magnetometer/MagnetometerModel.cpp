// SPDX-License-Identifier: Apache-2.0
#include "components/magnetometer/MagnetometerModel.hpp"

#include <cmath>
#include <stdexcept>

#include "components/common/Validation.hpp"

namespace flatsat::magnetometer {

std::vector<std::string> MagnetometerParams::validate() const {
  std::vector<std::string> errors;
  requireNonNegative(errors, "noise_T", noise_T);
  requireFinite(errors, "bias_B_T", bias_B_T);
  requireAllPositive(errors, "scale_factor", scale_factor, "axis");
  requireNonNegative(errors, "quantum_T", quantum_T);
  requirePositive(errors, "range_T", range_T);
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
