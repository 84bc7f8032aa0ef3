// SPDX-License-Identifier: Apache-2.0
#include "sim/DynamicsServerParams.hpp"

#include <cmath>
#include <filesystem>
#include <string>

#include "sim/Constants.hpp"
#include "sim/SunEphemeris.hpp"

namespace flatsat::sim {

namespace {

namespace fs = std::filesystem;

std::string findDataFile(const bus::Scenario& scenario, const std::string& name) {
  const fs::path given(name);
  if (given.is_absolute()) return name;
  const fs::path beside = fs::path(scenario.file).parent_path() / given;
  if (fs::exists(beside)) return beside.string();
  for (const char* dir : {FLATSAT_SOURCE_DATA_DIR, FLATSAT_INSTALL_DATA_DIR}) {
    if (fs::exists(fs::path(dir) / given)) return (fs::path(dir) / given).string();
  }
  return name;
}

void readOrbit(bus::ParamReader orbit, DynamicsParams& p) {
  std::string epoch = "2026-03-20T00:00:00Z";
  orbit.read("epoch_utc", epoch);
  try {
    p.epoch = parseIso8601Utc(epoch);
  } catch (const std::invalid_argument& e) {
    orbit.problem("epoch_utc", e.what());
  }
  double altitude_m = 0.0;
  orbit.read("altitude_m", altitude_m, "m");
  orbit.read("semi_major_axis_m", p.orbit.semi_major_axis_m, "m");
  if (orbit.has("altitude_m") == orbit.has("semi_major_axis_m")) {
    orbit.problem("", "give exactly one of altitude_m (circular) or semi_major_axis_m");
  } else if (orbit.has("altitude_m")) {
    p.orbit.semi_major_axis_m = kEarthEquatorialRadius_m + altitude_m;
  }
  orbit.read("eccentricity", p.orbit.eccentricity, "-");
  orbit.read("inclination_rad", p.orbit.inclination_rad, "rad");
  orbit.read("raan_rad", p.orbit.raan_rad, "rad");
  orbit.read("arg_perigee_rad", p.orbit.arg_perigee_rad, "rad");
  orbit.read("mean_anomaly_rad", p.orbit.mean_anomaly_rad, "rad");
  orbit.problems(p.orbit.validate());
  orbit.finish();
}

/// Optical and accommodation fractions, shared by panels and flaps.
template <class Surface>
void readSurface(bus::ParamReader& reader, Surface& surface) {
  reader.read("specular", surface.specular, "-");
  reader.read("diffuse", surface.diffuse, "-");
  reader.read("absorbed", surface.absorbed, "-");
  reader.read("aero_specular", surface.aero_specular, "-");
}

/// spacecraft.panels: a list of mappings, one per panel.
void readPanels(bus::ParamReader& spacecraft, DynamicsParams& p) {
  for (auto& reader : spacecraft.list("panels")) {
    Panel panel;
    reader.read("area_m2", panel.area_m2, "m^2");
    reader.read("normal_body", panel.normal_B, "-");
    reader.read("cp_body_m", panel.r_cp_B_m, "m");
    readSurface(reader, panel);
    reader.problems(panel.validate());
    reader.finish();
    p.panels.push_back(panel);
  }
}

/// spacecraft.thrusters: a list of mappings; a `gimbal` mapping makes the
/// thruster gimballed.
void readThrusters(bus::ParamReader& spacecraft, DynamicsParams& p) {
  for (auto& reader : spacecraft.list("thrusters")) {
    ThrusterParams thruster;
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
    reader.problems(thruster.validate());
    reader.finish();
    p.thrusters.push_back(thruster);
  }
}

void readSpacecraft(bus::ParamReader spacecraft, DynamicsParams& p) {
  spacecraft.read("inertia_kg_m2", p.body.J_B_kg_m2, "kg m^2");
  spacecraft.read("residual_dipole_body_Am2", p.residual_dipole_B_Am2, "A m^2");
  auto wheels = spacecraft.section("wheels");
  wheels.read("axes_body", p.body.wheel_axes_B, p.body.wheel_count);
  wheels.read("inertia_kg_m2", p.body.wheel_inertia_kg_m2, "kg m^2");
  wheels.read("max_torque_Nm", p.body.wheel_max_torque_Nm, "N m");
  wheels.read("max_momentum_Nms", p.body.wheel_max_momentum_Nms, "N m s");
  wheels.read("viscous_friction_Nms_per_rad", p.body.wheel_viscous_friction_Nms_rad, "N m s/rad");
  wheels.read("coulomb_friction_Nm", p.body.wheel_coulomb_friction_Nm, "N m");
  // A scalar applies to every wheel; slots beyond the count stay empty.
  for (int i = p.body.wheel_count; i < kMaxWheels; ++i) {
    p.body.wheel_inertia_kg_m2[i] = p.body.wheel_max_torque_Nm[i] = 0.0;
    p.body.wheel_max_momentum_Nms[i] = 0.0;
    p.body.wheel_viscous_friction_Nms_rad[i] = p.body.wheel_coulomb_friction_Nm[i] = 0.0;
  }
  wheels.finish();
  auto torquers = spacecraft.section("torquers");
  torquers.read("max_dipole_Am2", p.torquer_max_dipole_Am2, "A m^2");
  torquers.finish();
  readPanels(spacecraft, p);
  readThrusters(spacecraft, p);
  auto flaps = spacecraft.section("flaps");
  p.flaps.fitted = spacecraft.has("flaps");
  flaps.read("plate_area_m2", p.flaps.plate_area_m2, "m^2");
  flaps.read("lever_arm_m", p.flaps.lever_arm_m, "m");
  flaps.read("max_angle_rad", p.flaps.max_angle_rad, "rad");
  readSurface(flaps, p.flaps);
  flaps.problems(p.flaps.validate());
  flaps.finish();
  spacecraft.problems(p.body.validate());
  spacecraft.finish();
}

void readEnvironment(const bus::Scenario& scenario, bus::ParamReader environment,
                     DynamicsParams& p) {
  std::string igrf_file = "igrf/igrf14coeffs.txt";
  environment.read("igrf_file", igrf_file);
  try {
    p.field = igrfDipoleAt(findDataFile(scenario, igrf_file), decimalYear(p.epoch));
  } catch (const std::exception& e) {
    environment.problem("igrf_file", e.what());
  }
  environment.read("gravity_gradient", p.gravity_gradient);
  // Constant until the atmosphere model is connected.
  environment.read("density_kg_m3", p.density_kg_m3, "kg/m^3");
  environment.read("disturbance_torque_body_Nm", p.disturbance_torque_B_Nm, "N m");
  environment.finish();
}

/// An attitude whose body axis `axis_B` is `offset` away from the Sun at the
/// epoch: the state a coarse Sun acquisition hands to fine pointing.
Eigen::Quaterniond sunOffsetAttitude(const DynamicsParams& p, const Eigen::Vector3d& axis_B,
                                     double offset_rad) {
  const double jd_tt = julianDate(p.epoch) + kTtMinusUtc_s / 86400.0;
  const Eigen::Vector3d r_sat = KeplerOrbit(p.orbit).at(0.0).r_N_m;
  const Eigen::Vector3d sun_N = (sunPosition_N_m(jd_tt) - r_sat).normalized();
  const Eigen::Quaterniond align = Eigen::Quaterniond::FromTwoVectors(axis_B, sun_N);
  const Eigen::Vector3d tilt_axis_B = axis_B.unitOrthogonal();
  return (align * Eigen::Quaterniond(Eigen::AngleAxisd(offset_rad, tilt_axis_B))).normalized();
}

void readInitial(bus::ParamReader initial, DynamicsParams& p) {
  initial.read("q_inertial_body", p.q0_NB);
  double offset_rad = 0.0;
  Eigen::Vector3d axis_B = Eigen::Vector3d::UnitX();
  initial.read("sun_offset_rad", offset_rad, "rad");
  initial.read("sun_offset_axis_body", axis_B, "-");
  if (initial.has("sun_offset_rad")) {
    if (initial.has("q_inertial_body")) {
      initial.problem("", "give q_inertial_body or sun_offset_rad, not both");
    } else if (axis_B.norm() < 1e-9) {
      initial.problem("sun_offset_axis_body", "must be a non-zero vector");
    } else if (p.orbit.validate().empty()) {
      p.q0_NB = sunOffsetAttitude(p, axis_B.normalized(), offset_rad);
    }
  }
  initial.read("w_body_rad_s", p.w0_NB_B_rad_s, "rad/s");
  initial.read("wheel_speed_rad_s", p.wheel_speed0_rad_s, "rad/s");
  initial.finish();
}

}  // namespace

DynamicsParams readPlant(const bus::Scenario& scenario, bus::ConfigProblems& problems) {
  DynamicsParams p;
  readOrbit(scenario.section("orbit", problems), p);
  readSpacecraft(scenario.section("spacecraft", problems), p);
  readEnvironment(scenario, scenario.section("environment", problems), p);
  readInitial(scenario.section("initial", problems), p);
  return p;
}

DynamicsServerParams readDynamicsServerParams(const bus::Scenario& scenario,
                                              const std::string& name,
                                              bus::ConfigProblems& problems) {
  DynamicsServerParams params;
  DynamicsParams& p = params.dynamics;
  p = readPlant(scenario, problems);
  auto own = scenario.componentParams(name, problems);
  own.read("substeps", p.substeps);
  own.problems(p.validate());
  own.finish();

  params.step_period_ns = fromSeconds(scenario.step_s);
  if (p.orbit.validate().empty()) params.orbit_period_s = KeplerOrbit(p.orbit).period_s();
  const double duration_s = scenario.duration_s > 0
                                ? scenario.duration_s
                                : scenario.duration_orbits * params.orbit_period_s;
  params.final_step = static_cast<std::uint64_t>(std::llround(duration_s / scenario.step_s));
  return params;
}

}  // namespace flatsat::sim
