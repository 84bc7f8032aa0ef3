// SPDX-License-Identifier: Apache-2.0
#include "components/sun_sensor/SunSensorModel.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Geometry>

#include "components/common/Validation.hpp"

namespace flatsat::sun_sensor {

std::vector<std::string> SunSensorParams::validate() const {
  std::vector<std::string> errors;
  requireUnit(errors, "boresight_B", boresight_B);
  requireNonNegative(errors, "noise_rad", noise_rad);
  // Below π/2 because the transverse angles are rebuilt through their tangents.
  require(errors, fov_half_angle_rad > 0.0 && fov_half_angle_rad < std::numbers::pi / 2.0,
          "fov_half_angle_rad", "must be in (0, pi/2)");
  require(errors, min_illumination >= 0.0 && min_illumination <= 1.0, "min_illumination",
          "must be in [0, 1]");
  return errors;
}

SunSensorModel::SunSensorModel(const Params& params)
    : params_(params), t1_B_(Eigen::Vector3d::Zero()), t2_B_(Eigen::Vector3d::Zero()),
      cos_fov_(std::cos(params.fov_half_angle_rad)), noise_(params.seed) {
  if (const auto errors = params_.validate(); !errors.empty()) {
    std::string message = "SunSensorParams invalid:";
    for (const auto& e : errors) {
      message += " " + e + ";";
    }
    throw std::invalid_argument(message);
  }
  params_.boresight_B.normalize();
  t1_B_ = params_.boresight_B.unitOrthogonal();
  t2_B_ = params_.boresight_B.cross(t1_B_);
}

void SunSensorModel::reset() { noise_.reset(); }

SunSensorOutput SunSensorModel::step(const Input& in, std::int64_t /*t_ns*/) {
  // Drawn on every call so the noise sequence does not depend on eclipses or the FOV.
  const Eigen::Vector2d angle_noise_rad = noise_.vector<2>(params_.noise_rad);

  Output out;
  const double norm = in.sun_B_unit.norm();
  if (!(in.illumination >= params_.min_illumination) || !(norm > 0.0)) {
    return out;
  }
  const Eigen::Vector3d s = in.sun_B_unit / norm;
  const double along = s.dot(params_.boresight_B);
  if (!(along >= cos_fov_)) {
    return out;
  }
  // A real detector cannot report an angle beyond its FOV; the clamp also keeps tan() finite.
  const double fov = params_.fov_half_angle_rad;
  const double alpha = std::clamp(std::atan2(s.dot(t1_B_), along) + angle_noise_rad.x(), -fov, fov);
  const double beta = std::clamp(std::atan2(s.dot(t2_B_), along) + angle_noise_rad.y(), -fov, fov);
  out.sun_B_unit =
      (params_.boresight_B + std::tan(alpha) * t1_B_ + std::tan(beta) * t2_B_).normalized();
  out.valid = true;
  return out;
}

}  // namespace flatsat::sun_sensor
