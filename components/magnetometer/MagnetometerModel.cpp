// SPDX-License-Identifier: Apache-2.0
#include "components/magnetometer/MagnetometerModel.hpp"

#include <cmath>

#include <Eigen/Geometry>
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
  requireFinite(errors, "misalignment_rad", misalignment_rad);
  require(errors, misalignment_rad.norm() < M_PI, "misalignment_rad", "must be a rotation of less than pi");
  require(errors, coil_coupling_T_per_Am2.allFinite(), "coil_coupling_T_per_Am2", "must be finite");
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
  const double angle = params_.misalignment_rad.norm();
  const Eigen::Matrix3d R_SB =
      angle > 0.0 ? Eigen::AngleAxisd(-angle, params_.misalignment_rad / angle).toRotationMatrix()
                  : Eigen::Matrix3d::Identity();  // passive: a vector's components in the turned axes
  const Eigen::Vector3d at_sensor_T = R_SB * (in.b_B_T + params_.coil_coupling_T_per_Am2 * in.dipole_B_Am2);
  Eigen::Vector3d b = params_.scale_factor.cwiseProduct(at_sensor_T) + params_.bias_B_T +
                      noise_.vector<3>(params_.noise_T);
  if (params_.quantum_T > 0.0) {
    b = (b / params_.quantum_T).array().round() * params_.quantum_T;
  }
  // Clip after quantising so the output never leaves ±range_T, like an ADC's end code.
  Output out;
  out.blanked = params_.blank_while_coils_on && !in.dipole_B_Am2.isZero(0.0);
  out.saturated = (b.array().abs() > params_.range_T).any();
  out.b_B_T = b.cwiseMax(-params_.range_T).cwiseMin(params_.range_T);
  return out;
}

}  // namespace flatsat::magnetometer
