// SPDX-License-Identifier: Apache-2.0
#include "vehicle/VehicleDescription.hpp"

#include <cmath>

namespace flatsat::vehicle {
namespace {

constexpr double kUnitNormTolerance = 1e-6;

void appendNested(const std::string& prefix, const std::vector<std::string>& nested, std::vector<std::string>& errors) {
  for (const std::string& error : nested) errors.push_back(prefix + "." + error);
}

bool isUnit(double norm) { return std::isfinite(norm) && std::abs(norm - 1.0) < kUnitNormTolerance; }

}  // namespace

std::vector<std::string> SensorMountings::validate() const {
  std::vector<std::string> errors;
  if (!isUnit(sun_sensor_boresight_B.norm())) errors.push_back("sun_sensor_boresight_B: must be a unit vector");
  if (!isUnit(q_body_star_tracker.norm())) errors.push_back("q_body_star_tracker: must be a unit quaternion");
  if (!isUnit(q_body_magnetometer.norm())) errors.push_back("q_body_magnetometer: must be a unit quaternion");
  return errors;
}

std::vector<std::string> FieldModel::validate() const {
  std::vector<std::string> errors;
  if (!std::isfinite(dipole.g10_nT) || !std::isfinite(dipole.g11_nT) || !std::isfinite(dipole.h11_nT)) {
    errors.push_back("dipole: Gauss coefficients must be finite");
  }
  if (degree < 1 || degree > sim::GaussCoefficients::kMaxDegree) {
    errors.push_back("degree: " + std::to_string(degree) + " must be in 1..13");
  }
  return errors;
}

std::vector<std::string> VehicleDescription::validate() const {
  std::vector<std::string> errors;
  appendNested("epoch", epoch.validate(), errors);
  appendNested("orbit", orbit.validate(), errors);
  appendNested("orbit_track", orbit_track.validate(), errors);
  appendNested("field", field.validate(), errors);
  appendNested("body", body.validate(), errors);
  if (!torquer_max_dipole_Am2.allFinite() || (torquer_max_dipole_Am2.array() < 0.0).any()) {
    errors.push_back("torquer_max_dipole_Am2: every coil limit must be finite and ≥ 0");
  }
  for (std::size_t i = 0; i < panels.size(); ++i) {
    appendNested("panels[" + std::to_string(i) + "]", panels[i].validate(), errors);
  }
  if (thrusters.size() > static_cast<std::size_t>(sim::kMaxThrusters)) {
    errors.push_back("thrusters: " + std::to_string(thrusters.size()) + " thrusters, at most " +
                     std::to_string(sim::kMaxThrusters));
  }
  for (std::size_t i = 0; i < thrusters.size(); ++i) {
    appendNested("thrusters[" + std::to_string(i) + "]", thrusters[i].validate(), errors);
  }
  appendNested("flaps", flaps.validate(), errors);
  if (atmosphere) appendNested("atmosphere", atmosphere->validate(), errors);
  if (!(density_kg_m3 >= 0.0 && std::isfinite(density_kg_m3))) errors.push_back("density_kg_m3: must be finite and ≥ 0");
  if (orbit_track.propagator == sim::OrbitPropagation::kNumerical && orbit_track.forces.drag && !atmosphere) {
    errors.push_back("orbit_track.forces.drag: needs an atmosphere model (the constant density is for the panels only)");
  }
  if (!residual_dipole_B_Am2.allFinite()) errors.push_back("residual_dipole_B_Am2: must be finite");
  appendNested("sensors", sensors.validate(), errors);
  const int thruster_count = static_cast<int>(thrusters.size());
  for (std::size_t i = 0; i < faults.size(); ++i) {
    appendNested("faults[" + std::to_string(i) + "]", faults[i].validate(body.wheel_count, thruster_count), errors);
  }
  return errors;
}

}  // namespace flatsat::vehicle
