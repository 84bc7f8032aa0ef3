// SPDX-License-Identifier: Apache-2.0
#include "tools/Composed.hpp"

#include <chrono>
#include <filesystem>
#include <memory>

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>

#include "bus/Composed.hpp"
#include "bus/LocalHub.hpp"
#include "bus/NodeMain.hpp"
#include "components/Registry.hpp"
#include "tools/Progress.hpp"

namespace flatsat::tools {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// The components' log file as the default logger while the rig runs.
class ComposedLog {
 public:
  ComposedLog(const fs::path& file, const std::string& level) : previous_(spdlog::default_logger()) {
    auto logger = spdlog::basic_logger_mt("composed", file.string(), true);
    logger->set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
    logger->set_level(spdlog::level::from_str(level));
    spdlog::set_default_logger(logger);
  }
  ~ComposedLog() {
    spdlog::set_default_logger(previous_);
    spdlog::drop("composed");
  }
  ComposedLog(const ComposedLog&) = delete;
  ComposedLog& operator=(const ComposedLog&) = delete;

 private:
  std::shared_ptr<spdlog::logger> previous_;
};

}  // namespace

std::vector<std::string> composedProblems(const bus::Scenario& scenario) {
  std::vector<std::string> problems;
  if (scenario.pacing == bus::Pacing::kPaced) {
    problems.push_back("mode: paced: a composed rig runs lockstep only (paced steps follow "
                       "the wall clock, which needs every component its own process)");
  }
  for (const auto& c : scenario.components) {
    const ComponentKind* kind = findComponentKind(c.name);
    if (!c.launched) {
      problems.push_back("components." + c.name +
                         ": role: external: it runs outside the rig and meets it over DDS, "
                         "which a composed rig does not open");
    } else if (kind != nullptr && !kind->make) {
      problems.push_back("components." + c.name + ": " + kind->not_composable +
                         "; it needs its own process (run without --composed)");
    }
  }
  return problems;
}

LaunchResult runComposed(const bus::Scenario& scenario, const LaunchOptions& options) {
  LaunchResult result;
  const auto start = Clock::now();
  const fs::path logs = fs::path(options.run_dir) / "logs";
  fs::create_directories(logs);
  const ComposedLog log(logs / "composed.log", options.log_level);

  // Declared in this order so that the nodes go first, then their buses, then the hub.
  bus::LocalHub hub;
  std::vector<std::unique_ptr<bus::Bus>> buses;
  std::vector<std::unique_ptr<bus::Node>> nodes;
  const auto newBus = [&](const std::string& name) -> bus::Bus& {
    buses.push_back(std::make_unique<bus::Bus>(
        bus::BusOptions{0, bus::NetworkProfile::kLoopback, name,
                        bus::qosTuning(scenario, bus::kEmulatorStrength), {}},
        hub));
    return *buses.back();
  };
  Progress progress(newBus("flatsat-launcher"), options.progress);
  bus::TimeMaster* master = nullptr;
  std::vector<bus::Component*> components;
  try {
    for (const auto& c : scenario.components) {
      bus::NodeOptions node_options = bus::nodeOptions(scenario, c.name);
      // One thread runs every node: a wait that is not over at once would
      // wait for itself, so it fails at once, naming what is missing.
      node_options.peer_timeout = std::chrono::milliseconds(0);
      node_options.step_timeout = std::chrono::milliseconds(0);
      nodes.push_back(findComponentKind(c.name)->make(
          newBus(c.name), std::move(node_options), scenario,
          {options.scenario_file, c.name, options.run_dir}));
      if (auto* m = dynamic_cast<bus::TimeMaster*>(nodes.back().get())) master = m;
      else if (auto* component = dynamic_cast<bus::Component*>(nodes.back().get())) components.push_back(component);
    }
    if (master == nullptr) throw bus::NodeFailure("the scenario has no time master");
    spdlog::info("composed {} components on one thread", nodes.size());
    bus::ComposedScheduler scheduler(*master, components);
    auto next_print = Clock::now();
    scheduler.run([&](std::uint64_t) {
      if (!options.progress) return;
      if (const auto now = Clock::now(); now >= next_print) {
        progress.print(false);
        next_print = now + std::chrono::milliseconds(500);
      }
    });
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    result.failure = std::string("composed rig: ") + e.what();
  }
  nodes.clear();  // closes the recording before the summary reads it
  progress.print(true);
  result.launch_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  result.step_seconds = progress.stepSeconds();
  result.startup_seconds = progress.startupSeconds(start);
  result.steps = progress.steps();
  result.processes = 1;
  result.ok = result.failure.empty();
  return result;
}

}  // namespace flatsat::tools
