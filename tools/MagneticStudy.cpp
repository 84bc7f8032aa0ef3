// SPDX-License-Identifier: Apache-2.0
#include "tools/MagneticStudy.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "bus/Scenario.hpp"
#include "components/magnetometer/MagnetometerNode.hpp"
#include "components/unloading_controller/UnloadingControllerNode.hpp"
#include "tools/Conventions.hpp"
#include "tools/MagneticMetrics.hpp"
#include "components/dynamics_server/DynamicsServerParams.hpp"
#include "sim/DynamicsModel.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::tools {
namespace {

namespace fs = std::filesystem;

struct StudyOptions {
  std::string kind;  // detumble | spin
  std::string scenario;
  int cases = 50;
};

std::string defaultScenario(const std::string& kind) {
  const std::string file = kind == "spin" ? "s4_spin.yaml" : "detumble.yaml";
  for (const char* dir : {FLATSAT_SOURCE_SCENARIO_DIR, FLATSAT_INSTALL_SCENARIO_DIR}) {
    if (fs::exists(fs::path(dir) / file)) return (fs::path(dir) / file).string();
  }
  return "deploy/scenarios/" + file;
}

std::uint32_t dividerOf(const bus::Scenario& scenario, const std::string& name) {
  for (const auto& c : scenario.components) {
    if (c.name == name) return c.rate_divider;
  }
  return 1;
}

struct CaseResult {
  MagneticMetricsResult metrics;
  std::optional<double> handover_s;
  double orbit_period_s = 0.0;
  double fifth_orbit_axis_deg = 0.0;      // worst spin-axis error over orbit 5 (4 to 5 periods)
  double fifth_orbit_rate_pct = 0.0;      // worst spin-rate error over orbit 5
};

/// One seed: the rig's dataflow in one process. At step k the magnetometer
/// samples truth(k), the controller answers from that sample, and the dipole is
/// held over [k, k+1) — as the lockstep rig does.
CaseResult runCase(bus::Scenario scenario, std::uint64_t seed) {
  scenario.seed = seed;
  bus::ConfigProblems problems;
  const vehicle::Vehicle craft = vehicle::readVehicle(scenario, problems);
  const auto server = dynamics_server::readParams(scenario, craft, {scenario.file, "dynamics_server", ""}, problems);
  const auto node = unloading_controller::readParams(scenario, craft, {scenario.file, "unloading_controller", ""}, problems);
  const auto& control = node.modes;
  const auto sensor = magnetometer::readParams(scenario, {scenario.file, "magnetometer", ""}, problems);
  if (!problems.empty()) throw std::invalid_argument(problems.joined());

  sim::DynamicsModel model(server.dynamics);
  magnetometer::MagnetometerModel field_sensor(sensor.model);
  unloading_controller::MagneticModes modes(control);
  std::optional<onboard::ReferenceModel> onboard;
  if (node.onboard) onboard.emplace(*node.onboard);
  MagneticMetricsParams judge;
  judge.max_dipole_Am2 = control.unload.max_dipole_Am2;
  const bool spin = control.initial_mode == unloading_controller::MagneticMode::kSpinCapture ||
                    control.after_detumble == unloading_controller::MagneticMode::kSpinCapture;
  if (spin) {
    judge.spin_axis_B = control.spin.spin_axis_B;
    judge.spin_rate_rad_s = control.spin.spin_rate_rad_s;
  }
  MagneticMetrics metrics(judge);
  const std::uint32_t sensor_divider = dividerOf(scenario, "magnetometer");
  const std::uint32_t control_divider = dividerOf(scenario, "unloading_controller");

  CaseResult result;
  result.orbit_period_s = server.orbit_period_s;
  magnetometer::MagnetometerOutput reading;
  sim::ActuatorCommands cmd;
  for (std::uint64_t k = 0; k < server.final_step; ++k) {
    const sim::Truth& truth = model.truth();
    if (k % sensor_divider == 0) reading = field_sensor.step({truth.b_B_T}, truth.t);
    if (k % control_divider == 0) {
      unloading_controller::MagneticModesInput in{truth.wheel_speed_rad_s, reading.b_B_T, !reading.saturated, std::nullopt};
      if (onboard) {
        const auto reference = onboard->step(truth.t);
        in.onboard = unloading_controller::OnboardField{reference.b_N_T, reference.orbit_normal_N_unit};
      }
      const auto out = modes.step(in, truth.t);
      cmd.dipole_B_Am2 = out.m_B_Am2;
      if (out.handover) result.handover_s = sim::toSeconds(truth.t);
    }
    model.step(cmd, truth.t + server.step_period_ns);
    const sim::Truth& after = model.truth();
    metrics.add(sim::toSeconds(after.t), after.q_NB, after.w_NB_B_rad_s, after.r_N_m, after.v_N_m_s,
                after.dipole_applied_B_Am2);
    const double orbits = sim::toSeconds(after.t) / server.orbit_period_s;
    if (orbits >= 4.0 && orbits <= 5.0) {
      const auto now = metrics.result();
      result.fifth_orbit_axis_deg = std::max(result.fifth_orbit_axis_deg, now.spin_axis_error_deg);
      result.fifth_orbit_rate_pct = std::max(result.fifth_orbit_rate_pct, now.spin_rate_error_pct);
    }
  }
  result.metrics = metrics.result();
  return result;
}

std::string orNone(const std::optional<double>& v) {
  char text[32];
  if (!v) return "never";
  std::snprintf(text, sizeof text, "%.0f", *v);
  return text;
}

int runStudy(const StudyOptions& o) {
  if (o.kind != "detumble" && o.kind != "spin") {
    std::cerr << "error: study '" << o.kind << "': choose detumble or spin\n";
    return kExitBadInput;
  }
  bus::Scenario scenario;
  try {
    scenario = bus::loadScenario(o.scenario.empty() ? defaultScenario(o.kind) : o.scenario);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitBadInput;
  }
  const bool spin = o.kind == "spin";
  const double limit_orbits = spin ? 5.0 : 3.0;
  std::printf("study %s: %s, %d seeded cases (seed = case), step %.3g s\n", o.kind.c_str(),
              scenario.file.c_str(), o.cases, scenario.step_s);
  std::printf(spin ? "| seed | handover [s] | capture [s] | capture [orbits] | axis err [deg] | rate err [%%] "
                     "| orbit 5 worst axis err [deg] | orbit 5 worst rate err [%%] | coil duty |\n"
                     "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
                   : "| seed | detumbled [s] | detumbled [orbits] | final rate [deg/s] | coil duty |\n"
                     "|---:|---:|---:|---:|---:|\n");
  int passed = 0;
  double worst_orbits = 0.0, duty_sum = 0.0;
  for (int seed = 1; seed <= o.cases; ++seed) {
    CaseResult c;
    try {
      c = runCase(scenario, static_cast<std::uint64_t>(seed));
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return kExitBadInput;
    }
    const auto& m = c.metrics;
    const auto time = spin ? m.time_to_capture_s : m.time_to_detumble_s;
    const double orbits = time ? *time / c.orbit_period_s : INFINITY;
    passed += orbits <= limit_orbits ? 1 : 0;
    worst_orbits = std::max(worst_orbits, orbits);
    duty_sum += m.coil_duty;
    if (spin) {
      std::printf("| %d | %s | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.3f |\n", seed,
                  orNone(c.handover_s).c_str(), orNone(time).c_str(), orbits, m.spin_axis_error_deg,
                  m.spin_rate_error_pct, c.fifth_orbit_axis_deg, c.fifth_orbit_rate_pct, m.coil_duty);
    } else {
      std::printf("| %d | %s | %.2f | %.3f | %.3f |\n", seed, orNone(time).c_str(), orbits,
                  m.rate_deg_s_final, m.coil_duty);
    }
  }
  std::printf("passed %d/%d (within %.0f orbits, held to the end); worst %.2f orbits; mean coil duty %.3f\n",
              passed, o.cases, limit_orbits, worst_orbits, duty_sum / o.cases);
  return 0;
}

}  // namespace

void addMagneticStudies(CLI::App& study, int& exit_code) {
  for (const char* kind : {"detumble", "spin"}) {
    auto options = std::make_shared<StudyOptions>();
    options->kind = kind;
    auto* cmd = study.add_subcommand(
        kind, std::string(kind) == "spin" ? "S4 spin capture: seeded tumbles, time to capture, coil duty"
                                          : "B-dot detumble: seeded tumbles, time to detumble, coil duty");
    cmd->add_option("--cases", options->cases, "seeds 1..N")->capture_default_str()->check(CLI::PositiveNumber);
    cmd->add_option("--scenario", options->scenario, "scenario (default: detumble.yaml or s4_spin.yaml)");
    cmd->callback([options, &exit_code] { exit_code = runStudy(*options); });
  }
}

}  // namespace flatsat::tools
