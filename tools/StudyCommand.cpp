// SPDX-License-Identifier: Apache-2.0
#include "tools/ScenarioName.hpp"
#include "bus/InstallPaths.hpp"
#include "tools/StudyCommand.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include "components/sun_sensor/SunSensorNode.hpp"
#include "components/thruster_sequencer/AngleOnlyCase.hpp"
#include "components/thruster_sequencer/ThrusterSequencerNode.hpp"
#include "analysis/Conventions.hpp"
#include "tools/MagneticStudyCommand.hpp"
#include "analysis/Quantile.hpp"
#include "rig/RunDirectory.hpp"
#include "analysis/FieldFromMomentumStudy.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::tools {

using rig::writeRunScenario;
using analysis::FieldFromMomentumStudyOptions;
using analysis::kDeg;
using analysis::quantile;
using analysis::runFieldFromMomentumStudy;

namespace {

namespace fs = std::filesystem;
namespace ts = thruster_sequencer;

struct StudyOptions {
  std::string scenario = bus::installedScenario("s1_example.yaml");
  std::vector<std::string> overrides;
  int cases = 200;
  std::uint64_t seed = 20260320;
  double max_angle_deg = 45.0;
  double max_rate_deg_s = 2.0;
  double disturbance_Nm = 0.01;
  double duration_s = 1200.0;
};

void printRow(const char* what, const std::vector<double>& values) {
  std::printf("  %-18s %10.1f %10.1f %10.1f %10.1f\n", what, quantile(values, 0.0), quantile(values, 0.5),
              quantile(values, 0.9), quantile(values, 1.0));
}

/// Loads the scenario with its overrides through a scratch copy, as `flatsat run` does.
bool loadStudyScenario(const StudyOptions& o, bus::Scenario& scenario) {
  const fs::path scratch = fs::temp_directory_path() / ("flatsat-study-" + std::to_string(::getpid()));
  try {
    scenario = bus::loadScenario(writeRunScenario(o.scenario, scratch.string(), o.overrides));
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    fs::remove_all(scratch);
    return false;
  }
  fs::remove_all(scratch);
  return true;
}

int runStudy(const StudyOptions& o) {
  bus::Scenario scenario;
  if (!loadStudyScenario(o, scenario)) return 2;
  if (!scenario.hasComponent("thruster_sequencer") || !scenario.hasComponent("sun_sensor")) {
    std::cerr << "error: " << o.scenario << ": the study needs a thruster_sequencer and a sun_sensor\n";
    return 2;
  }
  bus::ConfigProblems problems;
  const vehicle::Vehicle craft = vehicle::readVehicle(scenario, problems);
  const auto sequencer_params = ts::readParams(scenario, craft, {scenario.file, "thruster_sequencer", ""}, problems);
  if (sequencer_params.mode != ts::ThrusterSequencerParams::Mode::kAngleOnly) {
    problems.add(o.scenario + ": components.thruster_sequencer.mode: the S1 study needs angle_only");
  }
  const auto& params = sequencer_params.angle_only;
  const auto sensor = sun_sensor::readParams(scenario, craft, {scenario.file, "sun_sensor", ""}, problems);
  if (!problems.empty() || o.cases < 1) {
    for (const auto& p : problems.list()) std::cerr << "error: " << p << "\n";
    if (o.cases < 1) std::cerr << "error: --cases must be >= 1\n";
    return 2;
  }
  const ts::AngleOnlySequencer sequencer(params);
  std::printf("S1 study: %d cases, angle within ±%.1f deg, rate within ±%.2f deg/s, %.0f s each, seed %llu\n",
              o.cases, o.max_angle_deg, o.max_rate_deg_s, o.duration_s, static_cast<unsigned long long>(o.seed));
  std::printf("  limits [%.3f, %.3f] deg, T1 %.2f s, T2 %.2f s, pulse %.3f s -> delta-omega %.4f deg/s, FOV %.1f deg\n",
              params.cycle.lower_limit_rad / kDeg, params.cycle.upper_limit_rad / kDeg,
              params.cycle.correction_interval_s, params.cycle.braking_interval_s, params.pulse_on_time_s,
              sequencer.pulseDeltaRate_rad_s(1) / kDeg, sensor.model.fov_half_angle_rad / kDeg);
  bool all_settled = true;
  for (const double disturbance_Nm : {0.0, o.disturbance_Nm}) {
    std::vector<double> pulses, pulses_to_settle, settle_s, excursion_deg;
    int settled = 0;
    for (auto c : ts::seededCases(o.seed, o.cases, o.max_angle_deg * kDeg, o.max_rate_deg_s * kDeg,
                                  disturbance_Nm, o.duration_s)) {
      c.fov_half_angle_rad = sensor.model.fov_half_angle_rad;
      const auto r = ts::runAngleOnlyCase(params, c);
      settled += r.settled;
      pulses.push_back(r.pulses.total);
      pulses_to_settle.push_back(r.pulses_to_settle);
      settle_s.push_back(r.settle_time_s);
      excursion_deg.push_back(r.max_angle_rad / kDeg);
    }
    all_settled = all_settled && settled == o.cases;
    std::printf("\ndisturbance %.4g N m about the axis: settled %d / %d\n", disturbance_Nm, settled, o.cases);
    std::printf("  %-18s %10s %10s %10s %10s\n", "", "min", "median", "p90", "max");
    printRow("pulses to settle", pulses_to_settle);
    printRow("pulses in all", pulses);
    printRow("settle time [s]", settle_s);
    printRow("max |angle| [deg]", excursion_deg);
  }
  return all_settled ? 0 : 1;
}

}  // namespace

CLI::App* addStudyCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<StudyOptions>();
  auto* study = app.add_subcommand("study", "algorithm-level studies that print tables");
  study->require_subcommand(1);
  auto* s1 = study->add_subcommand("s1", "S1 angle-only limit cycle: seeded initial angles and rates, settle statistics");
  s1->add_option("scenario", options->scenario, "scenario with a thruster_sequencer")->transform(scenarioByName())->capture_default_str();
  s1->add_option("--set", options->overrides, "override a scenario key: key.path=value");
  s1->add_option("--cases", options->cases, "cases per disturbance")->capture_default_str();
  s1->add_option("--seed", options->seed, "random seed of the cases")->capture_default_str();
  s1->add_option("--max-angle-deg", options->max_angle_deg, "initial angle bound [deg]")->capture_default_str();
  s1->add_option("--max-rate-deg-s", options->max_rate_deg_s, "initial rate bound [deg/s]")->capture_default_str();
  s1->add_option("--disturbance-Nm", options->disturbance_Nm, "constant torque of the second set [N m]")
      ->capture_default_str();
  s1->add_option("--duration-s", options->duration_s, "simulated time per case [s]")->capture_default_str();
  s1->callback([options, &exit_code] { exit_code = runStudy(*options); });

  auto s0_options = std::make_shared<FieldFromMomentumStudyOptions>();
  s0_options->scenario = bus::installedScenario("s0_no_magnetometer.yaml");
  auto* s0 = study->add_subcommand("s0", "S0 field and roll accuracy over window lengths and dipoles");
  s0->add_option("scenario", s0_options->scenario, "scenario (plant, sensors, attitude loop)")->transform(scenarioByName())->capture_default_str();
  s0->add_option("--orbits", s0_options->orbits, "simulated orbits per case")->capture_default_str();
  s0->add_option("--cycle-s", s0_options->cycle_s, "seconds from one window to the next")->capture_default_str();
  s0->add_option("--form", s0_options->form, "one case only: seed | settle | settle+q | total+q");
  s0->add_option("--window-s", s0_options->window_s, "one case only: quiet = pulse length [s]")
      ->check(CLI::PositiveNumber);
  s0->add_option("--dipole-Am2", s0_options->dipole_Am2, "one case only: x dipole [A m^2]")
      ->check(CLI::PositiveNumber);
  s0->callback([s0_options, &exit_code] { exit_code = runFieldFromMomentumStudy(*s0_options); });

  addMagneticStudies(*study, exit_code);
  return study;
}

}  // namespace flatsat::tools
