// SPDX-License-Identifier: Apache-2.0
#include "rig/Fleet.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>

#include "bus/Bus.hpp"
#include "bus/Shutdown.hpp"
#include "rig/ComposedRun.hpp"
#include "rig/Spawn.hpp"
#include "analysis/Summary.hpp"

namespace flatsat::rig {

using analysis::summarize;

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// The keys of a summary that describe the run rather than the spacecraft.
const std::vector<std::string> kRunKeys = {"scenario",        "sim_seconds",     "wall_seconds",
                                           "launch_seconds",  "startup_seconds", "speed_factor",
                                           "steps",           "steps_per_second", "processes"};

std::string logOf(const LaunchOptions& options, std::uint32_t i) {
  return (fs::path(options.run_dir) / "logs" / ("spacecraft-" + std::to_string(i) + ".log")).string();
}

nlohmann::ordered_json readSummary(const std::string& dir) {
  nlohmann::ordered_json summary;
  std::ifstream(fs::path(dir) / "summary.json") >> summary;
  return summary;
}

}  // namespace

LaunchResult launchFleet(const bus::Scenario& scenario, const LaunchOptions& options) {
  LaunchResult result;
  const auto start = Clock::now();
  const std::uint32_t count = scenario.spacecraft_count;
  const std::uint32_t base = bus::domainFromEnvironment(scenario.domain_id);
  if (base + count - 1 > 232) {
    result.failure = "spacecraft_count: " + std::to_string(count) + " spacecraft from domain " +
                     std::to_string(base) + " go past the last DDS domain, 232";
    return result;
  }
  fs::create_directories(fs::path(options.run_dir) / "logs");
  const std::string exe = fs::canonical("/proc/self/exe").string();
  std::map<pid_t, std::uint32_t> running;
  const auto stopAll = [&] {
    for (const auto& [pid, i] : running) ::kill(pid, SIGTERM);
  };
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::string dir = spacecraftDirectory(options.run_dir, count, i);
    try {
      // Each rig its own domain: FLATSAT_DOMAIN outranks the scenario's domain_id.
      const pid_t pid = spawnLogged({"env", "FLATSAT_DOMAIN=" + std::to_string(base + i), exe, "run",
                                     options.scenario_file, "--set", "spacecraft_count=1", "--set",
                                     "seed=" + std::to_string(spacecraftScenario(scenario, i).seed), "--out",
                                     dir, "--no-plots", "-q", "--log", options.log_level},
                                    logOf(options, i));
      running[pid] = i;
    } catch (const std::runtime_error& e) {
      result.failure = "spacecraft " + std::to_string(i) + ": " + e.what();
      stopAll();
      break;
    }
  }
  while (!running.empty()) {
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno != EINTR) break;
      if (bus::shutdownRequested() && result.failure.empty()) {
        result.failure = "interrupted";
        stopAll();
      }
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const std::uint32_t i = it->second;
    running.erase(it);
    const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (!ok && result.failure.empty()) {
      result.failure =
          "spacecraft " + std::to_string(i) + " failed (" + describeExit(status) + "); see " + logOf(options, i);
      stopAll();
    }
  }
  result.launch_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (!result.failure.empty()) return result;
  // The rigs ran side by side: the run took as long as the slowest of them.
  for (std::uint32_t i = 0; i < count; ++i) {
    const auto summary = readSummary(spacecraftDirectory(options.run_dir, count, i));
    result.step_seconds = std::max(result.step_seconds, summary["wall_seconds"].get<double>());
    result.startup_seconds = std::max(result.startup_seconds, summary["startup_seconds"].get<double>());
    result.processes += summary["processes"].get<std::size_t>();
    if (i == 0) result.steps = summary["steps"].get<std::uint64_t>();
  }
  result.ok = true;
  return result;
}

nlohmann::ordered_json fleetSummary(const bus::Scenario& scenario, const std::string& run_dir,
                                    const LaunchResult& result) {
  const std::uint32_t count = scenario.spacecraft_count;
  nlohmann::ordered_json each = nlohmann::ordered_json::array();
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::string dir = spacecraftDirectory(run_dir, count, i);
    // A rig of processes wrote its own; a composed one left it to this run.
    nlohmann::ordered_json summary;
    if (fs::exists(fs::path(dir) / "summary.json")) {
      summary = readSummary(dir);
    } else {
      summary = summarize(spacecraftScenario(scenario, i), (fs::path(dir) / "recording.sqlite").string(), result);
      std::ofstream(fs::path(dir) / "summary.json") << summary.dump(2) << "\n";
    }
    each.push_back(summary);
  }
  nlohmann::ordered_json s;
  for (const auto& key : kRunKeys) s[key] = each[0][key];
  const double sim_seconds = each[0]["sim_seconds"].get<double>();
  s["wall_seconds"] = result.step_seconds;
  s["launch_seconds"] = result.launch_seconds;
  s["startup_seconds"] = result.startup_seconds;
  s["speed_factor"] = result.step_seconds > 0 ? sim_seconds / result.step_seconds : 0.0;
  s["steps"] = result.steps;
  const double steps_per_second =
      result.step_seconds > 0 ? static_cast<double>(result.steps) / result.step_seconds : 0.0;
  s["steps_per_second"] = steps_per_second;
  s["processes"] = result.processes;
  s["spacecraft_count"] = count;
  // The fleet completed when every spacecraft did; the first that did not says why.
  s["completed"] = std::all_of(each.begin(), each.end(), [](const auto& one) { return one.value("completed", false); });
  s["end_reason"] = "completed";
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!each[i].value("completed", false)) {
      s["end_reason"] = "spacecraft " + std::to_string(i) + ": " + each[i].value("end_reason", std::string("?"));
      break;
    }
  }
  std::uint64_t intruders = 0;
  for (const auto& one : each) intruders += one.value("intruders", std::uint64_t{0});
  s["intruders"] = intruders;
  s["spacecraft_steps_per_second"] = steps_per_second * count;
  for (auto& summary : each) {
    for (const auto& key : kRunKeys) summary.erase(key);
  }
  s["spacecraft"] = each;
  return s;
}

}  // namespace flatsat::rig
