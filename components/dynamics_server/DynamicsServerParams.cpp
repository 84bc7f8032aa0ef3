// SPDX-License-Identifier: Apache-2.0
#include "components/dynamics_server/DynamicsServerParams.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bus/Topics.hpp"
#include "sim/Frames.hpp"
#include "sim/InitialDispersion.hpp"
#include "sim/SunEphemeris.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::dynamics_server {

using namespace sim;  // the plant's types, throughout

namespace {

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

DynamicsParams truthPlant(const vehicle::VehicleDescription& truth) {
  DynamicsParams p;
  p.epoch = truth.epoch;
  p.orbit = truth.orbit;
  p.orbit_track = truth.orbit_track;
  p.body = truth.body;
  p.field_model = truth.field.spherical_harmonics ? FieldModel::kSphericalHarmonics : FieldModel::kTiltedDipole;
  p.field = truth.field.dipole;
  p.field_harmonics = truth.field.harmonics;
  p.field_degree = truth.field.degree;
  p.torquer_max_dipole_Am2 = truth.torquer_max_dipole_Am2;
  p.residual_dipole_B_Am2 = truth.residual_dipole_B_Am2;
  p.panels = truth.panels;
  p.thrusters = truth.thrusters;
  p.flaps = truth.flaps;
  p.atmosphere = truth.atmosphere;
  p.density_kg_m3 = truth.density_kg_m3;
  return p;
}

DynamicsServerParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  DynamicsServerParams params;
  DynamicsParams& p = params.dynamics;
  p = truthPlant(vehicle.truth);
  const std::size_t problems_before = problems.list().size();
  params.faults = vehicle.truth.faults;
  auto environment = scenario.section("environment", problems);
  environment.read("gravity_gradient", p.gravity_gradient);
  environment.read("disturbance_torque_body_Nm", p.disturbance_torque_B_Nm, "N m");
  environment.leave(vehicle::kEnvironmentKeys);
  environment.finish();
  readInitial(scenario.section("initial", problems), p, scenario.seedFor("initial"));

  auto own = scenario.componentParams(args.name, problems);
  vehicle::refuseMovedKeys(own, {{"faults", "spacecraft.faults"}});
  own.read("substeps", p.substeps);
  own.read("wheels_follow", params.wheels_follow);
  const std::string wheel_unit = std::string(bus::topics::kWheelTach.producer) + "_bridge";
  if (!params.wheels_follow.empty()) {
    if (params.wheels_follow != wheel_unit) {
      own.problem("wheels_follow", "'" + params.wheels_follow + "' is not a wheel unit's bridge (" + wheel_unit + ")");
    } else if (!scenario.hasComponent(params.wheels_follow)) {
      own.problem("wheels_follow", "the scenario has no component " + params.wheels_follow);
    } else if (scenario.pacing != bus::Pacing::kPaced) {
      own.problem("wheels_follow", "a unit on a serial line runs on the wall clock: needs mode: paced");
    } else if (p.body.wheel_count < 1) {
      own.problem("wheels_follow", "the spacecraft has no wheels (spacecraft.wheels)");
    }
  }
  std::string attitude = "free";
  own.read("attitude", attitude);
  if (attitude == "held_east_north_zenith") {
    p.attitude_held = true;
  } else if (attitude != "free") {
    own.problem("attitude", "'" + attitude + "' is neither free nor held_east_north_zenith");
  }
  // The vehicle reader reports the vehicle's problems; of validate()'s, the
  // server reports its own keys' (the initial state, substeps), the initial
  // state's only when its section read cleanly (its reader names the key).
  const bool initial_read = problems.list().size() == problems_before;
  for (const std::string& error : p.validate()) {
    const auto owns = [&](const char* field) { return error.rfind(field, 0) == 0; };
    const bool initial = owns("q0_NB") || owns("w0_NB_B_rad_s") || owns("wheel_speed0_rad_s") ||
                         owns("disturbance_torque_B_Nm");
    if (owns("substeps") || (initial && initial_read)) own.problems({error});
  }
  own.finish();

  params.step_period_ns = fromSeconds(scenario.step_s);
  if (p.orbit.validate().empty()) params.orbit_period_s = KeplerOrbit(p.orbit).period_s();
  const double duration_s = scenario.duration_s > 0
                                ? scenario.duration_s
                                : scenario.duration_orbits * params.orbit_period_s;
  const double steps = duration_s / scenario.step_s;
  if (!(steps <= bus::kMaxRunSteps)) {  // also a NaN from an orbit that failed its own checks
    if (p.orbit.validate().empty()) {
      char text[96];
      std::snprintf(text, sizeof text, "%.3g steps of %g s: more than a run steps (1e9)", steps, scenario.step_s);
      problems.add(scenario.file + ": " + (scenario.duration_s > 0 ? "duration_s" : "duration_orbits") + ": " + text);
    }
    return params;
  }
  params.final_step = static_cast<std::uint64_t>(std::llround(steps));
  return params;
}

}  // namespace flatsat::dynamics_server
