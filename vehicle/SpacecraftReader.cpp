// SPDX-License-Identifier: Apache-2.0
// The spacecraft section: inertia, wheels, torquers, the orbit's mass and
// areas, panels, thrusters, flaps, sensor mountings and actuator faults.
#include <string>
#include <utility>
#include <vector>

#include "bus/FaultFields.hpp"
#include "vehicle/ReaderSections.hpp"

namespace flatsat::vehicle {

using sim::OrbitForceParams;
using sim::OrbitTrackParams;
using sim::Panel;
using sim::ThrusterParams;

namespace {

/// The errors of `errors` that start with `prefix`, without it.
std::vector<std::string> withPrefix(const std::vector<std::string>& errors, const std::string& prefix) {
  std::vector<std::string> selected;
  for (const std::string& error : errors) {
    if (error.rfind(prefix, 0) == 0) selected.push_back(error.substr(prefix.size()));
  }
  return selected;
}

/// Optical and accommodation fractions, shared by panels and flaps.
template <class Surface>
void readSurface(bus::ParamReader& reader, Surface& surface) {
  reader.read("specular", surface.specular, "-");
  reader.read("diffuse", surface.diffuse, "-");
  reader.read("absorbed", surface.absorbed, "-");
  reader.read("aero_specular", surface.aero_specular, "-");
}

/// A list of mappings, one Item each: `fields` reads an entry's keys, then the
/// item is validated and unknown keys are reported.
template <class Item, class ReadFields>
std::vector<Item> readList(bus::ParamReader& parent, const std::string& key, ReadFields fields) {
  std::vector<Item> items;
  for (auto& reader : parent.list(key)) {
    Item item;
    fields(reader, item);
    reader.problems(item.validate());
    reader.finish();
    items.push_back(item);
  }
  return items;
}

/// One entry of spacecraft.panels.
void readPanel(bus::ParamReader& reader, Panel& panel) {
  reader.read("area_m2", panel.area_m2, "m^2");
  reader.read("normal_body", panel.normal_B, "-");
  reader.read("cp_body_m", panel.r_cp_B_m, "m");
  reader.read("sun_tracking_axis_body", panel.sun_tracking_axis_B, "-");
  readSurface(reader, panel);
}

/// One entry of spacecraft.thrusters; a `gimbal` mapping makes it gimballed.
void readThruster(bus::ParamReader& reader, ThrusterParams& thruster) {
  reader.read("position_body_m", thruster.r_B_m, "m");
  reader.read("direction_body", thruster.direction_B, "-");
  reader.read("thrust_N", thruster.thrust_N, "N");
  reader.read("min_impulse_bit_Ns", thruster.min_impulse_bit_Ns, "N s");
  reader.read("failed", thruster.failed);
  thruster.gimballed = reader.has("gimbal");
  auto gimbal = reader.section("gimbal");
  gimbal.read("axis_1_body", thruster.gimbal_axis1_B, "-");
  gimbal.read("min_1_rad", thruster.gimbal_min_rad[0], "rad");
  gimbal.read("max_1_rad", thruster.gimbal_max_rad[0], "rad");
  gimbal.read("axis_2_body", thruster.gimbal_axis2_B, "-");
  gimbal.read("min_2_rad", thruster.gimbal_min_rad[1], "rad");
  gimbal.read("max_2_rad", thruster.gimbal_max_rad[1], "rad");
  gimbal.finish();
}

/// Mass, cannonball areas and coefficients of the numerical orbit; each is
/// required when a force that is on uses it.
void readOrbitProperties(bus::ParamReader& spacecraft, OrbitTrackParams& track) {
  OrbitForceParams& f = track.forces;
  spacecraft.read("mass_kg", f.mass_kg, "kg");
  spacecraft.read("drag_area_m2", f.drag_area_m2, "m^2");
  spacecraft.read("drag_coefficient", f.drag_coefficient, "-");
  spacecraft.read("srp_area_m2", f.srp_area_m2, "m^2");
  spacecraft.read("reflectivity_coefficient", f.reflectivity_coefficient, "-");
  if (track.propagator != sim::OrbitPropagation::kNumerical) return;
  const std::pair<const char*, bool> needed[] = {
      {"mass_kg", true}, {"drag_area_m2", f.drag}, {"srp_area_m2", f.solar_pressure}};
  for (const auto& [key, is_needed] : needed) {
    if (is_needed && !spacecraft.has(key)) spacecraft.problem(key, "needed by the numerical orbit (orbit.propagator)");
  }
  spacecraft.problems(withPrefix(track.validate(), "forces."));
}

}  // namespace

void readSpacecraft(bus::ParamReader spacecraft, VehicleDescription& p) {
  spacecraft.read("inertia_kg_m2", p.body.J_B_kg_m2, "kg m^2");
  readOrbitProperties(spacecraft, p.orbit_track);
  spacecraft.read("residual_dipole_body_Am2", p.residual_dipole_B_Am2, "A m^2");
  auto wheels = spacecraft.section("wheels");
  wheels.read("axes_body", p.body.wheel_axes_B, p.body.wheel_count);
  wheels.read("inertia_kg_m2", p.body.wheel_inertia_kg_m2, "kg m^2");
  wheels.read("max_torque_Nm", p.body.wheel_max_torque_Nm, "N m");
  wheels.read("max_momentum_Nms", p.body.wheel_max_momentum_Nms, "N m s");
  wheels.read("viscous_friction_Nms_per_rad", p.body.wheel_viscous_friction_Nms_rad, "N m s/rad");
  wheels.read("coulomb_friction_Nm", p.body.wheel_coulomb_friction_Nm, "N m");
  // A scalar applies to every wheel; slots beyond the count stay empty.
  for (int i = p.body.wheel_count; i < sim::kMaxWheels; ++i) {
    p.body.wheel_inertia_kg_m2[i] = p.body.wheel_max_torque_Nm[i] = 0.0;
    p.body.wheel_max_momentum_Nms[i] = 0.0;
    p.body.wheel_viscous_friction_Nms_rad[i] = p.body.wheel_coulomb_friction_Nm[i] = 0.0;
  }
  wheels.finish();
  auto torquers = spacecraft.section("torquers");
  torquers.read("max_dipole_Am2", p.torquer_max_dipole_Am2, "A m^2");
  torquers.finish();
  p.panels = readList<Panel>(spacecraft, "panels", readPanel);
  p.thrusters = readList<ThrusterParams>(spacecraft, "thrusters", readThruster);
  auto flaps = spacecraft.section("flaps");
  p.flaps.fitted = spacecraft.has("flaps");
  std::string wings = "y";
  flaps.read("wings_along", wings);
  if (const auto parsed = sim::flapWingsFromName(wings)) {
    p.flaps.wings = *parsed;
  } else {
    flaps.problem("wings_along", "'" + wings + "' is neither y (polar orbits: roll and yaw) nor z (equatorial: roll and pitch)");
  }
  flaps.read("plate_area_m2", p.flaps.plate_area_m2, "m^2");
  flaps.read("lever_arm_m", p.flaps.lever_arm_m, "m");
  flaps.read("max_angle_rad", p.flaps.max_angle_rad, "rad");
  readSurface(flaps, p.flaps);
  flaps.problems(p.flaps.validate());
  flaps.finish();
  spacecraft.problems(p.body.validate());
  readSensorMountings(spacecraft.section("sensors"), p.sensors);
  p.faults = readActuatorFaults(spacecraft, p);
  spacecraft.finish();
}

void readSensorMountings(bus::ParamReader sensors, SensorMountings& m) {
  auto sun = sensors.section("sun_sensor");
  sun.read("boresight_body", m.sun_sensor_boresight_B, "-");
  sun.finish();
  auto star = sensors.section("star_tracker");
  star.read("q_body_sensor", m.q_body_star_tracker);
  star.finish();
  auto magnetometer = sensors.section("magnetometer");
  magnetometer.read("q_body_sensor", m.q_body_magnetometer);
  magnetometer.finish();
  sensors.problems(m.validate());
  sensors.finish();
}

std::vector<sim::ActuatorFault> readActuatorFaults(bus::ParamReader& reader, const VehicleDescription& v) {
  const int wheels = v.body.wheel_count;
  const int thrusters = static_cast<int>(v.thrusters.size());
  return bus::readFaults<sim::ActuatorFault>(
      reader, "-", kActuatorFaultKinds, sim::ActuatorFaults::kMaxFaults, sim::parseActuatorFaultKind,
      [wheels, thrusters](const sim::ActuatorFault& f) { return f.validate(wheels, thrusters); });
}

}  // namespace flatsat::vehicle
