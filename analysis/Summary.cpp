// SPDX-License-Identifier: Apache-2.0
#include "analysis/Summary.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "analysis/RunFigures.hpp"
#include "analysis/SummaryTrust.hpp"
#include "bus/Recording.hpp"
#include "bus/RecordingMeta.hpp"

namespace flatsat::analysis {

namespace {

/// Copies a group of the recorded figures (analysis/RunFigures.hpp) into the summary, in its order.
void take(nlohmann::ordered_json& summary, const nlohmann::ordered_json& figures, const char* group) {
  if (!figures.contains(group)) return;
  for (const auto& [key, value] : figures[group].items()) summary[key] = value;
}

/// Each component's role in the scenario, and what a program off the bus did:
/// what its bridges published.
void addRoles(nlohmann::ordered_json& s, const bus::Scenario& scenario) {
  nlohmann::ordered_json roles = nlohmann::ordered_json::object();
  for (const auto& c : scenario.components) roles[c.name] = c.role;
  nlohmann::ordered_json programs = nlohmann::ordered_json::object();
  const nlohmann::ordered_json producers = s.value("topic_producers", nlohmann::ordered_json::object());
  for (const auto& program : scenario.programs) {
    roles[program.name] = "program";
    nlohmann::ordered_json topics = nlohmann::ordered_json::object();
    for (const auto& [topic, sources] : producers.items()) {
      for (const auto& bridge : program.bridges) {
        if (std::find(sources.begin(), sources.end(), bridge) != sources.end()) topics[topic] = bridge;
      }
    }
    programs[program.name] = {{"command", program.command}, {"topics", topics}};
  }
  s["roles"] = roles;
  if (!scenario.programs.empty()) s["programs"] = programs;
}

}  // namespace

nlohmann::ordered_json summarize(const bus::Scenario& scenario, const std::string& recording_path,
                                 const RunOutcome& launch) {
  const bus::Recording recording(recording_path, bus::Recording::Access::kRead);
  // Accumulated by the recorder while the run stepped; read back only when it could not be.
  const nlohmann::ordered_json figures = recordedFigures(scenario, recording);
  std::uint64_t steps = figures["extent"].value("steps", std::uint64_t{0});
  double sim_seconds = figures["extent"].value("sim_seconds", 0.0);

  // A decimated recording (recorder record_every_steps) holds every Nth truth
  // sample only: the run's extent is then the grants the launcher counted.
  const std::string every = recording.meta(bus::meta::kRecordEverySteps);
  if (!every.empty() && launch.steps > 0) {
    steps = launch.steps;
    sim_seconds = static_cast<double>(launch.steps - 1) * scenario.step_s;
  }

  nlohmann::ordered_json s;
  s["scenario"] = scenario.name;
  addCompletion(s, figures["grants"], every.empty() ? 1 : std::stoull(every));
  s["sim_seconds"] = sim_seconds;
  s["wall_seconds"] = launch.step_seconds;
  s["launch_seconds"] = launch.launch_seconds;
  s["startup_seconds"] = launch.startup_seconds;
  s["speed_factor"] = launch.step_seconds > 0 ? sim_seconds / launch.step_seconds : 0.0;
  s["steps"] = steps;
  s["steps_per_second"] = launch.step_seconds > 0 ? static_cast<double>(steps) / launch.step_seconds : 0.0;
  s["processes"] = launch.processes;
  s["acquisition_seconds"] = scenario.acquisition_s;
  s["mode"] = scenario.pacing == bus::Pacing::kPaced ? "paced" : "lockstep";
  take(s, figures, "truth");
  if (scenario.pacing == bus::Pacing::kPaced) {
    // How evenly the ticks came: each step grant's arrival at the launcher
    // against the period grid (rig/Progress.hpp TickJitter).
    s["tick_jitter_us_p50"] = launch.tick_jitter.p50_us;
    s["tick_jitter_us_p99"] = launch.tick_jitter.p99_us;
    s["tick_jitter_us_max"] = launch.tick_jitter.max_us;
    s["ticks_missed"] = launch.tick_jitter.missed;
    take(s, figures, "timing");
  }
  take(s, figures, "ownership");
  addRoles(s, scenario);
  // [s] from the launch to each external component's first health sample.
  s["external_joined_s"] = launch.external_joined_s;
  if (!launch.restarts.empty()) s["restarts"] = launch.restarts;
  for (const char* group : {"lateness", "trust", "s0", "magnetic", "aero", "station_keeping", "estimator"}) {
    take(s, figures, group);
  }
  s["recording"] = recording_path;
  // The recorder's, when it stored every sample in order: reading 355 MB back
  // to hash them was two thirds of a composed day's summary.
  const std::string kept = recording.meta(bus::meta::kDigest);
  s["recording_sha256"] = kept.empty() ? recording.digest() : kept;
  take(s, figures, "thruster");
  return s;
}

namespace {

/// "flatsat/magnetometer: magnetometer -> magnetometer_bridge at 12.3 s (gap 0.1 s)", the
/// first three, then how many in all.
std::string ownershipSwitches(const nlohmann::ordered_json& switches) {
  constexpr std::size_t kShown = 3;
  std::ostringstream out;
  for (std::size_t i = 0; i < std::min(kShown, switches.size()); ++i) {
    const auto& w = switches[i];
    char times[64];
    std::snprintf(times, sizeof times, " at %.6g s (gap %.3g s)", w.value("time_s", 0.0), w.value("gap_s", 0.0));
    out << (i > 0 ? "; " : "") << w.value("topic", "?") << ": " << w.value("from", "?") << " -> " << w.value("to", "?")
        << times;
  }
  if (switches.size() > kShown) out << "; " << switches.size() << " in all (summary.json)";
  return out.str();
}

}  // namespace

std::string summaryTable(const nlohmann::ordered_json& summary) {
  std::ostringstream out;
  std::size_t width = 0;
  for (const auto& [key, value] : summary.items()) width = std::max(width, key.size());
  for (const auto& [key, value] : summary.items()) {
    out << "  " << key << std::string(width - key.size() + 2, ' ');
    if (value.is_number_float()) {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.6g", value.get<double>());
      out << buffer;
    } else if (value.is_string()) {
      out << value.get<std::string>();
    } else if (key == "spacecraft" && value.is_array()) {
      out << value.size() << " summaries (spacecraft-<i>/summary.json)";
    } else if (key == "ownership_switches" && value.is_array() && !value.empty()) {
      out << ownershipSwitches(value);
    } else if (value.is_array() && !value.empty() && value.front().is_object()) {
      out << value.size() << " entries (summary.json)";
    } else {
      out << value.dump();
    }
    out << '\n';
  }
  return out.str();
}

}  // namespace flatsat::analysis
