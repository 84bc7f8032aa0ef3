// SPDX-License-Identifier: Apache-2.0
#include "sim/PanelModel.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "sim/Constants.hpp"
#include "sim/Format.hpp"

namespace flatsat::sim {
namespace {

// Inputs are rounded decimals from a scenario file: a unit normal or a sum of
// fractions that is one on paper is accepted within these.
constexpr double kUnitNormTolerance = 1e-6;
constexpr double kFractionSumTolerance = 1e-9;

bool isFraction(double value) { return std::isfinite(value) && value >= 0.0 && value <= 1.0; }

}  // namespace

std::vector<std::string> Panel::validate() const {
  std::vector<std::string> errors;
  if (!(area_m2 > 0.0) || !std::isfinite(area_m2)) errors.push_back("area_m2: " + formatNumber(area_m2) + " must be > 0");
  if (!normal_B.allFinite() || std::abs(normal_B.norm() - 1.0) > kUnitNormTolerance) {
    errors.push_back("normal_B: must be a unit vector (norm " + formatNumber(normal_B.norm()) + ")");
  }
  if (!r_cp_B_m.allFinite()) errors.push_back("r_cp_B_m: must be finite");
  if (!sun_tracking_axis_B.allFinite() ||
      (!sun_tracking_axis_B.isZero(0.0) && std::abs(sun_tracking_axis_B.norm() - 1.0) > kUnitNormTolerance)) {
    errors.push_back("sun_tracking_axis_B: must be zero or a unit vector (norm " +
                     formatNumber(sun_tracking_axis_B.norm()) + ")");
  }
  const char* names[] = {"specular", "diffuse", "absorbed", "aero_specular"};
  const double values[] = {specular, diffuse, absorbed, aero_specular};
  for (int i = 0; i < 4; ++i) {
    if (!isFraction(values[i])) errors.push_back(std::string(names[i]) + ": " + formatNumber(values[i]) + " not in [0, 1]");
  }
  const double sum = specular + diffuse + absorbed;
  if (std::isfinite(sum) && std::abs(sum - 1.0) > kFractionSumTolerance) {
    errors.push_back("absorbed: specular + diffuse + absorbed = " + formatNumber(sum) + " must be 1");
  }
  return errors;
}

Eigen::Vector3d Panel::trackedNormal(const Eigen::Vector3d& sun_B_unit) const {
  const Eigen::Vector3d across = sun_B_unit - sun_B_unit.dot(sun_tracking_axis_B) * sun_tracking_axis_B;
  // A Sun within ~0.06° of the axis leaves the drive where it was mounted.
  return across.norm() < 1e-3 ? normal_B : across.normalized();
}

double solarFlux_W_m2(double sun_distance_m, double illumination) {
  const double au_over_r = kAstronomicalUnit_m / sun_distance_m;
  return kSolarFlux1Au_W_m2 * illumination * au_over_r * au_over_r;
}

namespace {

// The per-panel parts, with what all panels share (flow speed and direction,
// radiation pressure) worked out once by the callers: the panel sums run five
// times a rig step (each RK4 stage and the truth).
ForceTorque aerodynamicOnPanel(const Panel& panel, double density_kg_m3, double speed, const Eigen::Vector3d& w_unit,
                               const Eigen::Vector3d& sun_B_unit) {
  const Eigen::Vector3d normal = panel.normalFacing(sun_B_unit);
  const double cos_alpha = -normal.dot(w_unit);
  if (cos_alpha <= 0.0) return {};  // the flow reaches only the other side
  const double scale = density_kg_m3 * speed * speed * panel.area_m2 * cos_alpha;
  const Eigen::Vector3d force =
      scale * ((1.0 - panel.aero_specular) * w_unit - 2.0 * panel.aero_specular * cos_alpha * normal);
  return ForceTorque{force, panel.r_cp_B_m.cross(force)};
}

ForceTorque solarPressureOnPanel(const Panel& panel, const Eigen::Vector3d& sun_B_unit, double pressure) {
  const Eigen::Vector3d normal = panel.normalFacing(sun_B_unit);
  const double cos_theta = normal.dot(sun_B_unit);
  if (cos_theta <= 0.0) return {};
  const Eigen::Vector3d force =
      -pressure * panel.area_m2 * cos_theta *
      ((1.0 - panel.specular) * sun_B_unit + 2.0 * (panel.specular * cos_theta + panel.diffuse / 3.0) * normal);
  return ForceTorque{force, panel.r_cp_B_m.cross(force)};
}

}  // namespace

ForceTorque aerodynamicForceTorque(const Panel& panel, double density_kg_m3, const Eigen::Vector3d& wind_B_m_s,
                                   const Eigen::Vector3d& sun_B_unit) {
  return aerodynamicForceTorque(std::span<const Panel>(&panel, 1), density_kg_m3, wind_B_m_s, sun_B_unit);
}

ForceTorque aerodynamicForceTorque(std::span<const Panel> panels, double density_kg_m3,
                                   const Eigen::Vector3d& wind_B_m_s, const Eigen::Vector3d& sun_B_unit) {
  const double speed = wind_B_m_s.norm();
  if (!(speed > 0.0) || !(density_kg_m3 > 0.0)) return {};
  const Eigen::Vector3d w_unit = wind_B_m_s / speed;
  ForceTorque total;
  for (const Panel& panel : panels) total += aerodynamicOnPanel(panel, density_kg_m3, speed, w_unit, sun_B_unit);
  return total;
}

ForceTorque solarPressureForceTorque(const Panel& panel, const Eigen::Vector3d& sun_B_unit, double flux_W_m2) {
  return solarPressureForceTorque(std::span<const Panel>(&panel, 1), sun_B_unit, flux_W_m2);
}

ForceTorque solarPressureForceTorque(std::span<const Panel> panels, const Eigen::Vector3d& sun_B_unit,
                                     double flux_W_m2) {
  if (!(flux_W_m2 > 0.0)) return {};
  const double pressure = flux_W_m2 / kSpeedOfLight_m_s;
  ForceTorque total;
  for (const Panel& panel : panels) total += solarPressureOnPanel(panel, sun_B_unit, pressure);
  return total;
}

}  // namespace flatsat::sim
