// SPDX-License-Identifier: Apache-2.0
#include "tools/ScenarioName.hpp"
#include "bus/InstallPaths.hpp"
#include "tools/MagneticStudyCommand.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "analysis/Conventions.hpp"
#include "analysis/MagneticStudy.hpp"
#include "bus/Scenario.hpp"

namespace flatsat::tools {
namespace {

namespace fs = std::filesystem;
using analysis::kExitBadInput;

struct MagneticStudyOptions {
  std::string kind;  // detumble | spin
  std::string scenario;
  int cases = 50;
};

std::string defaultScenario(const std::string& kind) {
  const std::string file = kind == "spin" ? "s4_spin.yaml" : "detumble.yaml";
  return bus::installedScenario(file);
}

std::string orNone(const std::optional<double>& v) {
  char text[32];
  if (!v) return "never";
  std::snprintf(text, sizeof text, "%.0f", *v);
  return text;
}

int runMagneticStudy(const MagneticStudyOptions& o) {
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
    analysis::MagneticCase c;
    try {
      c = analysis::runMagneticCase(scenario, static_cast<std::uint64_t>(seed));
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
    auto options = std::make_shared<MagneticStudyOptions>();
    options->kind = kind;
    auto* cmd = study.add_subcommand(
        kind, std::string(kind) == "spin" ? "S4 spin capture: seeded tumbles, time to capture, coil duty"
                                          : "B-dot detumble: seeded tumbles, time to detumble, coil duty");
    cmd->add_option("--cases", options->cases, "seeds 1..N")->capture_default_str()->check(CLI::PositiveNumber);
    cmd->add_option("--scenario", options->scenario, "scenario (default: detumble.yaml or s4_spin.yaml)")->transform(scenarioByName());
    cmd->callback([options, &exit_code] { exit_code = runMagneticStudy(*options); });
  }
}

}  // namespace flatsat::tools
