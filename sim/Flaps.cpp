// SPDX-License-Identifier: Apache-2.0
#include "sim/Flaps.hpp"

#include <algorithm>
#include <cmath>

#include "sim/Format.hpp"

namespace flatsat::sim {
namespace {

// Plate i (0-based here, 1-based in the seed) sits on the + wing (+y, or +z with the
// wings along z) for seed numbers 1 and 3, on the − wing for 2 and 4.
constexpr double wingSign(int i) { return i % 2 == 0 ? 1.0 : -1.0; }

/// The along-y layout → the body: a quarter turn about x for wings along z.
Eigen::Vector3d layout_B(const Eigen::Vector3d& along_y, FlapWings wings) {
  if (wings == FlapWings::kAlongY) return along_y;
  return {along_y.x(), -along_y.z(), along_y.y()};
}

}  // namespace

std::optional<FlapWings> flapWingsFromName(const std::string& name) {
  if (name == "y") return FlapWings::kAlongY;
  if (name == "z") return FlapWings::kAlongZ;
  return std::nullopt;
}

Eigen::Vector3d flapSecondAxis_B(FlapWings wings) { return layout_B(Eigen::Vector3d::UnitZ(), wings); }

Eigen::Vector3d flapTorqueShape_B(const Eigen::Vector2d& c, FlapWings wings) {
  return c.x() * Eigen::Vector3d::UnitX() + c.y() * flapSecondAxis_B(wings);
}

std::vector<std::string> FlapsParams::validate() const {
  std::vector<std::string> errors;
  if (!fitted) return errors;
  if (!(plate_area_m2 > 0.0) || !std::isfinite(plate_area_m2)) {
    errors.push_back("plate_area_m2: " + formatNumber(plate_area_m2) + " must be > 0");
  }
  if (!(lever_arm_m > 0.0) || !std::isfinite(lever_arm_m)) {
    errors.push_back("lever_arm_m: " + formatNumber(lever_arm_m) + " must be > 0");
  }
  if (!(max_angle_rad > 0.0) || max_angle_rad > std::numbers::pi / 2) {
    errors.push_back("max_angle_rad: " + formatNumber(max_angle_rad) + " not in (0, π/2]");
  }
  // The optical and accommodation fractions are a Panel's; its checks apply.
  Panel face;
  face.area_m2 = 1.0;
  face.specular = specular;
  face.diffuse = diffuse;
  face.absorbed = absorbed;
  face.aero_specular = aero_specular;
  for (const std::string& error : face.validate()) errors.push_back(error);
  return errors;
}

Flaps::Flaps(const FlapsParams& params) : params_(params) {}

Eigen::Vector4d Flaps::limitAngles(const Eigen::Vector4d& theta_cmd_rad) const {
  Eigen::Vector4d theta = Eigen::Vector4d::Zero();
  for (int i = 0; i < kFlapCount; ++i) {
    if (std::isfinite(theta_cmd_rad(i))) {
      theta(i) = std::clamp(theta_cmd_rad(i), -params_.max_angle_rad, params_.max_angle_rad);
    }
  }
  return theta;
}

std::array<Panel, kFlapPanelCount> Flaps::panels(const Eigen::Vector4d& theta_rad) const {
  std::array<Panel, kFlapPanelCount> faces;
  for (int i = 0; i < kFlapCount; ++i) {
    const double side = wingSign(i);
    Panel face;
    face.area_m2 = params_.plate_area_m2;
    face.normal_B = layout_B({side * std::sin(theta_rad(i)), 0.0, std::cos(theta_rad(i))}, params_.wings);
    face.r_cp_B_m = layout_B({0.0, side * params_.lever_arm_m, 0.0}, params_.wings);
    face.specular = params_.specular;
    face.diffuse = params_.diffuse;
    face.absorbed = params_.absorbed;
    face.aero_specular = params_.aero_specular;
    faces[static_cast<std::size_t>(2 * i)] = face;
    face.normal_B = -face.normal_B;
    faces[static_cast<std::size_t>(2 * i + 1)] = face;
  }
  return faces;
}

Eigen::Vector2d Flaps::normalisedTorques(const Eigen::Vector4d& theta_rad) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (int i = 0; i < kFlapCount; ++i) {
    const double s = std::abs(std::sin(theta_rad(i)));
    c(0) += 0.5 * std::sin(2.0 * theta_rad(i)) * s;
    c(1) += -wingSign(i) * s * s * s;  // (−1)^i with the seed's 1-based i
  }
  return c;
}

Eigen::Vector3d Flaps::nominalTorque_B_Nm(const Eigen::Vector4d& theta_rad, double density_kg_m3,
                                          double speed_m_s) const {
  const double scale = 2.0 * density_kg_m3 * params_.plate_area_m2 * speed_m_s * speed_m_s * params_.lever_arm_m;
  return scale * flapTorqueShape_B(normalisedTorques(theta_rad), params_.wings);
}

}  // namespace flatsat::sim
