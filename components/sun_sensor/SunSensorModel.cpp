// SPDX-License-Identifier: Apache-2.0
#include "components/sun_sensor/SunSensorModel.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>

#include "components/common/Validation.hpp"

namespace flatsat::sun_sensor {

std::vector<std::string> SunSensorParams::validate() const {
  std::vector<std::string> errors;
  requireUnit(errors, "boresight_B", boresight_B);
  if (boresight_onboard_B) requireUnit(errors, "boresight_onboard_B", *boresight_onboard_B);
  requireNonNegative(errors, "noise_rad", noise_rad);
  // Below π/2 because the transverse angles are rebuilt through their tangents.
  require(errors, fov_half_angle_rad > 0.0 && fov_half_angle_rad < std::numbers::pi / 2.0,
          "fov_half_angle_rad", "must be in (0, pi/2)");
  require(errors, min_illumination >= 0.0 && min_illumination <= 1.0, "min_illumination",
          "must be in [0, 1]");
  if (kind != SunSensorKind::kCoarseCosine) return errors;
  const auto& cells = cell_normals_B;
  require(errors, cells.size() >= 2 && cells.size() <= static_cast<std::size_t>(kMaxSunCells), "cells",
          "needs 2.." + std::to_string(kMaxSunCells) + " cells");
  bool paired = true;
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (const auto& n : cells) {
    requireUnit(errors, "cells[].normal_body", n);
    paired = paired && std::any_of(cells.begin(), cells.end(), [&](const Eigen::Vector3d& m) { return (m + n).norm() < 1e-6; });
    spread += n * n.transpose();
  }
  require(errors, paired, "cells", "every cell needs one facing the opposite way (pairs)");
  require(errors, Eigen::FullPivLU<Eigen::Matrix3d>(spread).rank() == 3, "cells",
          "the cells' normals must span three dimensions");
  requireNonNegative(errors, "cell_noise", cell_noise);
  requirePositive(errors, "min_output", min_output);
  if (albedo) {
    require(errors, albedo->albedo >= 0.0 && albedo->albedo <= 1.0, "albedo", "must be in [0, 1]");
  }
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
  if (params_.boresight_onboard_B && *params_.boresight_onboard_B != params_.boresight_B) {
    misknown_mounting_ = Eigen::Quaterniond::FromTwoVectors(params_.boresight_B, *params_.boresight_onboard_B);
  }
  params_.boresight_B.normalize();
  t1_B_ = params_.boresight_B.unitOrthogonal();
  t2_B_ = params_.boresight_B.cross(t1_B_);
  if (params_.kind == SunSensorKind::kCoarseCosine) {
    Eigen::MatrixXd N(params_.cell_normals_B.size(), 3);
    for (std::size_t i = 0; i < params_.cell_normals_B.size(); ++i) N.row(static_cast<Eigen::Index>(i)) = params_.cell_normals_B[i].transpose();
    cell_pinv_ = (N.transpose() * N).inverse() * N.transpose();
  }
}

void SunSensorModel::reset() { noise_.reset(); }

SunSensorOutput SunSensorModel::coarse(const Input& in) {
  Output out;
  const auto n = static_cast<int>(params_.cell_normals_B.size());
  out.cell_count = n;
  const double norm = in.sun_B_unit.norm();
  const Eigen::Vector3d s = norm > 0.0 ? Eigen::Vector3d(in.sun_B_unit / norm) : Eigen::Vector3d::Zero();
  // The Earth stays lit while the spacecraft is in its shadow: albedo at the 1 AU flux
  // (the Sun's distance changes it by ±3.4 % over the year).
  const bool albedo = params_.albedo && norm > 0.0 && in.r_B_m.norm() > 0.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d& cell = params_.cell_normals_B[static_cast<std::size_t>(i)];
    // Drawn for every cell on every call: the sequence does not depend on the geometry.
    const double noise = noise_.sample(params_.cell_noise);
    double value = in.flux_ratio * std::max(0.0, cell.dot(s));
    if (albedo) value += sim::albedoIrradiance(in.r_B_m, s, cell, *params_.albedo);
    out.cell_output[static_cast<std::size_t>(i)] = value + noise;
  }
  // f s / 2 for opposite pairs (see the header).
  const Eigen::Vector3d half = cell_pinv_ * Eigen::Map<const Eigen::VectorXd>(out.cell_output.data(), n);
  if (!(2.0 * half.norm() >= params_.min_output)) return out;
  out.sun_B_unit = half.normalized();
  out.valid = true;
  return out;
}

SunSensorOutput SunSensorModel::step(const Input& in, std::int64_t /*t_ns*/) {
  if (params_.kind == SunSensorKind::kCoarseCosine) return coarse(in);
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
  // The angles are turned into body axes on the mounting flight software believes.
  if (misknown_mounting_) out.sun_B_unit = *misknown_mounting_ * out.sun_B_unit;
  out.valid = true;
  return out;
}

}  // namespace flatsat::sun_sensor
