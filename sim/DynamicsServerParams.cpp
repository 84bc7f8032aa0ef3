// SPDX-License-Identifier: Apache-2.0
#include "sim/DynamicsServerParams.hpp"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "bus/FaultFields.hpp"
#include "sim/Constants.hpp"
#include "sim/DynamicsServerSections.hpp"
#include "sim/Frames.hpp"
#include "sim/GeomagneticCoefficients.hpp"
#include "sim/InitialDispersion.hpp"
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

/// orbit.propagator, orbit.step_s and the force switches orbit.forces.*; the
/// spacecraft's mass and areas are read with the spacecraft.
void readPropagator(bus::ParamReader& orbit, OrbitTrackParams& track) {
  std::string propagator = "kepler";
  orbit.read("propagator", propagator);
  if (propagator == "numerical") {
    track.propagator = OrbitPropagation::kNumerical;
  } else if (propagator != "kepler") {
    orbit.problem("propagator", "'" + propagator + "' is neither kepler nor numerical");
  }
  orbit.read("step_s", track.step_s, "s");
  auto forces = orbit.section("forces");
  OrbitForceParams& f = track.forces;
  forces.read("j2", f.j2);
  forces.read("j3", f.j3);
  forces.read("j4", f.j4);
  forces.read("j22", f.j22);
  forces.read("drag", f.drag);
  forces.read("solar_pressure", f.solar_pressure);
  forces.read("sun_gravity", f.sun_gravity);
  forces.read("moon_gravity", f.moon_gravity);
  forces.finish();
  if (track.propagator == OrbitPropagation::kKepler) {
    for (const char* key : {"step_s", "forces"}) {
      if (orbit.has(key)) orbit.problem(key, "only with propagator: numerical");
    }
  }
  // The forces' errors are the spacecraft's (mass, areas, coefficients).
  for (const std::string& error : track.validate()) {
    if (error.rfind("forces.", 0) != 0) orbit.problems({error});
  }
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
  readPropagator(orbit, p.orbit_track);
  orbit.finish();
}

/// environment.field_model and its files: the tilted dipole's coefficients
/// always come from the IGRF file (the onboard models use them too).
void readField(const bus::Scenario& scenario, bus::ParamReader& environment, DynamicsParams& p) {
  std::string model = "tilted_dipole";
  std::string igrf_file = "igrf/igrf14coeffs.txt";
  std::string wmm_file = "wmm/WMM2025.COF";
  environment.read("field_model", model);
  environment.read("igrf_file", igrf_file);
  environment.read("wmm_file", wmm_file);
  environment.read("field_degree", p.field_degree);
  const double year = decimalYear(p.epoch);
  const auto load = [&](const char* key, const std::string& file, auto loader) {
    try {
      p.field_harmonics = loader(findDataFile(scenario, file), year);
      p.field_model = FieldModel::kSphericalHarmonics;
    } catch (const std::exception& e) {
      environment.problem(key, e.what());
    }
  };
  bool igrf_read = false;
  try {
    p.field = igrfDipoleAt(findDataFile(scenario, igrf_file), year);
    igrf_read = true;
  } catch (const std::exception& e) {
    environment.problem("igrf_file", e.what());
  }
  if (model == "igrf14") {
    if (igrf_read) load("igrf_file", igrf_file, igrf14Coefficients);
  } else if (model == "wmm2025") {
    load("wmm_file", wmm_file, wmm2025Coefficients);
  } else if (model != "tilted_dipole") {
    environment.problem("field_model", "'" + model + "' is not tilted_dipole, igrf14 or wmm2025");
  }
  if (p.field_degree < 1 || p.field_degree > GaussCoefficients::kMaxDegree) {
    environment.problem("field_degree", std::to_string(p.field_degree) + " must be in 1..13");
  }
}

/// environment.atmosphere: constant (density_kg_m3) or a density model.
void readAtmosphere(const bus::Scenario& scenario, bus::ParamReader& environment, DynamicsParams& p) {
  std::string model = "constant";
  environment.read("atmosphere", model);
  AtmosphereParams atmosphere;
  environment.read("bulge_exponent", atmosphere.bulge_exponent, "-");
  // The solar activity: the table published for it (default: mean activity, M&G Table 3.8).
  std::string table_file;
  environment.read("harris_priester_table", table_file);
  if (!table_file.empty()) {
    try {
      atmosphere.harris_priester_table = readHarrisPriesterTable(findDataFile(scenario, table_file));
    } catch (const std::exception& e) {
      environment.problem("harris_priester_table", e.what());
    }
  }
  environment.read("density_kg_m3", p.density_kg_m3, "kg/m^3");
  if (model == "harris_priester" || model == "exponential") {
    atmosphere.model = model == "exponential" ? DensityModel::kExponential : DensityModel::kHarrisPriester;
    environment.problems(atmosphere.validate());
    p.atmosphere = atmosphere;
    if (environment.has("density_kg_m3")) environment.problem("density_kg_m3", "only with atmosphere: constant");
  } else if (model != "constant") {
    environment.problem("atmosphere", "'" + model + "' is not constant, harris_priester or exponential");
  }
  for (const char* key : {"bulge_exponent", "harris_priester_table"}) {
    if (model != "harris_priester" && environment.has(key)) environment.problem(key, "only with atmosphere: harris_priester");
  }
  const OrbitTrackParams& track = p.orbit_track;
  if (track.propagator == OrbitPropagation::kNumerical && track.forces.drag && !p.atmosphere) {
    environment.problem("atmosphere", "the numerical orbit's drag needs harris_priester or exponential");
  }
}

void readEnvironment(const bus::Scenario& scenario, bus::ParamReader environment, DynamicsParams& p) {
  readField(scenario, environment, p);
  readAtmosphere(scenario, environment, p);
  environment.read("gravity_gradient", p.gravity_gradient);
  environment.read("disturbance_torque_body_Nm", p.disturbance_torque_B_Nm, "N m");
  environment.finish();
}

/// An attitude whose body axis `axis_B` is `offset` away from the Sun at the
/// epoch, turned about the body axis `tilt_axis_B` (⟂ axis_B): the state a coarse
/// Sun acquisition hands to fine pointing.
Eigen::Quaterniond sunOffsetAttitude(const DynamicsParams& p, const Eigen::Vector3d& axis_B,
                                     const Eigen::Vector3d& tilt_axis_B, double offset_rad) {
  const double jd_tt = julianDate(p.epoch) + kTtMinusUtc_s / 86400.0;
  const Eigen::Vector3d r_sat = KeplerOrbit(p.orbit).at(0.0).r_N_m;
  const Eigen::Vector3d sun_N = (sunPosition_N_m(jd_tt) - r_sat).normalized();
  const Eigen::Quaterniond align = Eigen::Quaterniond::FromTwoVectors(axis_B, sun_N);
  return (align * Eigen::Quaterniond(Eigen::AngleAxisd(offset_rad, tilt_axis_B))).normalized();
}

/// initial.tumble_rate_rad_s: a tumble dispersed by the scenario's seed (`flatsat
/// run --seed N`): attitude uniform over SO(3), rate of that size about a uniform
/// axis (sim/InitialDispersion.hpp); it replaces the attitude and rate keys.
void readInitial(bus::ParamReader initial, DynamicsParams& p, std::uint64_t seed) {
  initial.read("q_inertial_body", p.q0_NB);
  double offset_rad = 0.0;
  Eigen::Vector3d axis_B = Eigen::Vector3d::UnitX();
  initial.read("sun_offset_rad", offset_rad, "rad");
  initial.read("sun_offset_axis_body", axis_B, "-");
  // The S1 checks turn the body about a chosen axis (its controlled axis); by default any
  // axis normal to the offset axis.
  Eigen::Vector3d tilt_axis_B = axis_B.norm() < 1e-9 ? Eigen::Vector3d::UnitY() : axis_B.unitOrthogonal();
  initial.read("sun_offset_tilt_axis_body", tilt_axis_B, "-");
  if (initial.has("sun_offset_rad")) {
    if (initial.has("q_inertial_body")) {
      initial.problem("", "give q_inertial_body or sun_offset_rad, not both");
    } else if (axis_B.norm() < 1e-9) {
      initial.problem("sun_offset_axis_body", "must be a non-zero vector");
    } else if (tilt_axis_B.norm() < 1e-9 || std::abs(tilt_axis_B.normalized().dot(axis_B.normalized())) > 1e-6) {
      initial.problem("sun_offset_tilt_axis_body", "must be a non-zero vector normal to sun_offset_axis_body");
    } else if (p.orbit.validate().empty()) {
      p.q0_NB = sunOffsetAttitude(p, axis_B.normalized(), tilt_axis_B.normalized(), offset_rad);
    }
  }
  // initial.attitude: s2_orbital starts in seed S2's orbital frame, turning with it,
  // then turned by s2_orbital_offset_rad about s2_orbital_offset_axis_body.
  std::string attitude;
  initial.read("attitude", attitude);
  double s2_offset_rad = 0.0;
  Eigen::Vector3d s2_offset_axis_B = Eigen::Vector3d::UnitX();
  initial.read("s2_orbital_offset_rad", s2_offset_rad, "rad");
  initial.read("s2_orbital_offset_axis_body", s2_offset_axis_B, "-");
  if (initial.has("attitude")) {
    if (attitude != "s2_orbital") {
      initial.problem("attitude", "'" + attitude + "' is not s2_orbital");
    } else if (initial.has("q_inertial_body") || initial.has("sun_offset_rad")) {
      initial.problem("attitude", "not with q_inertial_body or sun_offset_rad");
    } else if (!(s2_offset_axis_B.norm() > 0.0)) {
      initial.problem("s2_orbital_offset_axis_body", "must be a non-zero vector");
    } else if (p.orbit.validate().empty()) {
      const auto state = KeplerOrbit(p.orbit).at(0.0);
      const Eigen::Quaterniond q_NT(R_N_S2Orbital(state.r_N_m, state.v_N_m_s));
      p.q0_NB = (q_NT * Eigen::Quaterniond(Eigen::AngleAxisd(s2_offset_rad, s2_offset_axis_B.normalized())))
                    .normalized();
      p.w0_NB_B_rad_s = p.q0_NB.conjugate() * (state.r_N_m.cross(state.v_N_m_s) / state.r_N_m.squaredNorm());
    }
  }
  initial.read("w_body_rad_s", p.w0_NB_B_rad_s, "rad/s");
  initial.read("wheel_speed_rad_s", p.wheel_speed0_rad_s, "rad/s");
  double tumble_rate_rad_s = 0.0;
  initial.read("tumble_rate_rad_s", tumble_rate_rad_s, "rad/s");
  if (initial.has("tumble_rate_rad_s")) {
    for (const char* key : {"q_inertial_body", "sun_offset_rad", "w_body_rad_s", "attitude"}) {
      if (initial.has(key)) initial.problem(key, "not with tumble_rate_rad_s (the seed draws the tumble)");
    }
    if (!(tumble_rate_rad_s >= 0.0 && std::isfinite(tumble_rate_rad_s))) {
      initial.problem("tumble_rate_rad_s", "must be finite and >= 0");
    } else {
      const Tumble tumble = dispersedTumble(seed, tumble_rate_rad_s);
      p.q0_NB = tumble.q_NB;
      p.w0_NB_B_rad_s = tumble.w_NB_B_rad_s;
    }
  }
  initial.finish();
}

}  // namespace

DynamicsParams readPlant(const bus::Scenario& scenario, bus::ConfigProblems& problems) {
  DynamicsParams p;
  readOrbit(scenario.section("orbit", problems), p);
  readSpacecraft(scenario.section("spacecraft", problems), p);
  readEnvironment(scenario, scenario.section("environment", problems), p);
  readInitial(scenario.section("initial", problems), p, scenario.seedFor("initial"));
  return p;
}

namespace {

const std::string kActuatorFaultKinds = "wheel_failed, wheel_stuck, wheel_degraded, coil_open, thruster_failed";

auto validatorFor(int wheels, int thrusters) {
  return [wheels, thrusters](const ActuatorFault& f) { return f.validate(wheels, thrusters); };
}

}  // namespace

std::vector<ActuatorFault> readActuatorFaults(bus::ParamReader& reader, const DynamicsParams& plant) {
  return bus::readFaults<ActuatorFault>(reader, "-", kActuatorFaultKinds, ActuatorFaults::kMaxFaults,
                                        parseActuatorFaultKind,
                                        validatorFor(plant.body.wheel_count, static_cast<int>(plant.thrusters.size())));
}

std::vector<std::string> toActuatorFault(const msg::FaultCmd& command, int wheels, int thrusters,
                                         ActuatorFault& fault) {
  return bus::faultFromCommand(command, fault, kActuatorFaultKinds, parseActuatorFaultKind,
                               validatorFor(wheels, thrusters));
}

DynamicsServerParams readDynamicsServerParams(const bus::Scenario& scenario,
                                              const std::string& name,
                                              bus::ConfigProblems& problems) {
  DynamicsServerParams params;
  DynamicsParams& p = params.dynamics;
  const std::size_t problems_before = problems.list().size();
  p = readPlant(scenario, problems);
  const bool plant_read = problems.list().size() == problems_before;
  auto own = scenario.componentParams(name, problems);
  own.read("substeps", p.substeps);
  std::string attitude = "free";
  own.read("attitude", attitude);
  if (attitude == "held_east_north_zenith") {
    p.attitude_held = true;
  } else if (attitude != "free") {
    own.problem("attitude", "'" + attitude + "' is neither free nor held_east_north_zenith");
  }
  params.faults = readActuatorFaults(own, p);
  // The plant's sections report their own faults at their keys; validate() adds
  // only what they cannot see (the server's own keys, or anything once they are clean).
  for (const std::string& error : p.validate()) {
    if (plant_read || error.rfind("substeps", 0) == 0) own.problems({error});
  }
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
