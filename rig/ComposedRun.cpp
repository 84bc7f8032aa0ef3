// SPDX-License-Identifier: Apache-2.0
#include "rig/ComposedRun.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>

#include "bus/Composed.hpp"
#include "bus/LocalHub.hpp"
#include "bus/NodeMain.hpp"
#include "components/Registry.hpp"
#include "rig/Progress.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::rig {

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

namespace {

/// Steps one spacecraft runs before the next one runs the same steps.
constexpr std::uint64_t kStepsPerTurn = 512;

/// One spacecraft's rig: its nodes on their own hub, so that no sample of one
/// spacecraft reaches another (what a DDS domain of its own does for a rig
/// of processes). Members go in reverse: the nodes, then their buses, then the hub.
class ComposedRig {
 public:
  ComposedRig(const bus::Scenario& scenario, const LaunchOptions& options, const std::string& out_dir) {
    const vehicle::Vehicle vehicle = vehicle::vehicleOf(scenario);
    for (const auto& c : scenario.components) {
      bus::NodeOptions node_options = bus::nodeOptions(scenario, c.name);
      // One thread runs every node: a wait that is not over at once would
      // wait for itself, so it fails at once, naming what is missing.
      node_options.peer_timeout = std::chrono::milliseconds(0);
      node_options.step_timeout = std::chrono::milliseconds(0);
      nodes_.push_back(findComponentKind(c.name)->make(newBus(scenario, c.name), std::move(node_options),
                                                       scenario, vehicle, {options.scenario_file, c.name, out_dir}));
      if (auto* m = dynamic_cast<bus::TimeMaster*>(nodes_.back().get())) master_ = m;
      else if (auto* component = dynamic_cast<bus::Component*>(nodes_.back().get())) components_.push_back(component);
    }
    if (master_ == nullptr) throw bus::NodeFailure("the scenario has no time master");
    scheduler_ = std::make_unique<bus::ComposedScheduler>(*master_, components_);
  }
  bus::Bus& newBus(const bus::Scenario& scenario, const std::string& name) {
    buses_.push_back(std::make_unique<bus::Bus>(
        bus::BusOptions{0, bus::NetworkProfile::kLoopback, name,
                        bus::qosTuning(scenario, bus::kEmulatorStrength), {}},
        hub_));
    return *buses_.back();
  }
  bus::ComposedScheduler& scheduler() { return *scheduler_; }
  /// Its nodes started: every reader exists (LocalHub::seal).
  void seal() { hub_.seal(); }
  std::size_t size() const { return nodes_.size(); }
  /// Closes the recording, for the summary to read.
  void close() {
    scheduler_.reset();
    nodes_.clear();
  }

 private:
  bus::LocalHub hub_;
  std::vector<std::unique_ptr<bus::Bus>> buses_;
  std::vector<std::unique_ptr<bus::Node>> nodes_;
  bus::TimeMaster* master_ = nullptr;
  std::vector<bus::Component*> components_;
  std::unique_ptr<bus::ComposedScheduler> scheduler_;
};

}  // namespace

std::string spacecraftDirectory(const std::string& run_dir, std::uint32_t count, std::uint32_t i) {
  return count == 1 ? run_dir : (fs::path(run_dir) / ("spacecraft-" + std::to_string(i))).string();
}

bus::Scenario spacecraftScenario(const bus::Scenario& scenario, std::uint32_t i) {
  bus::Scenario one = scenario;
  one.seed += i;
  one.domain_id += i;
  return one;
}

LaunchResult runComposed(const bus::Scenario& scenario, const LaunchOptions& options) {
  LaunchResult result;
  const auto start = Clock::now();
  const fs::path logs = fs::path(options.run_dir) / "logs";
  fs::create_directories(logs);
  const ComposedLog log(logs / "composed.log", options.log_level);
  const std::uint32_t count = scenario.spacecraft_count;
  std::vector<std::unique_ptr<ComposedRig>> rigs;
  std::unique_ptr<Progress> progress;
  std::uint32_t current = 0;  // the spacecraft stepping, for an error's name
  double fleet_step_seconds = 0.0;  // [s] several spacecraft: first step to the last one's last
  const auto which = [&] { return count == 1 ? std::string() : "spacecraft " + std::to_string(current) + ": "; };
  try {
    for (current = 0; current < count; ++current) {
      const std::string out_dir = spacecraftDirectory(options.run_dir, count, current);
      fs::create_directories(out_dir);
      rigs.push_back(std::make_unique<ComposedRig>(spacecraftScenario(scenario, current), options, out_dir));
    }
    // Spacecraft 0's grants are the run's progress (they all step together).
    progress = std::make_unique<Progress>(rigs.front()->newBus(scenario, "flatsat-launcher"), options.progress);
    spdlog::info("composed {} spacecraft of {} components on one thread", count, rigs.front()->size());
    for (current = 0; current < count; ++current) {
      rigs[current]->scheduler().start();
      rigs[current]->seal();
    }
    const auto stepping = Clock::now();
    // The spacecraft do not meet, so each may run a block of steps before
    // the next one takes its turn: its nodes, models and recording stay in
    // the cache for the block instead of being pushed out by the others' at
    // every step (16 spacecraft stepped in turn cost 1.5 times as much per
    // spacecraft-step as one alone, 1.12 in blocks of 64 steps, 1.07 in
    // blocks of 512; flatsat bench --quick, fleet_n16_cost_growth).
    auto next_print = Clock::now();
    const std::uint64_t final_step = rigs.front()->scheduler().finalStep();
    for (std::uint64_t block = 0; block <= final_step; block += kStepsPerTurn) {
      const std::uint64_t last = std::min(final_step, block + kStepsPerTurn - 1);
      for (current = 0; current < count; ++current) {
        for (std::uint64_t k = block; k <= last; ++k) rigs[current]->scheduler().step(k);
      }
      if (!options.progress) continue;
      if (const auto now = Clock::now(); now >= next_print) {
        progress->print(false);
        next_print = now + std::chrono::milliseconds(500);
      }
    }
    // Spacecraft 0's grants span its own steps only: the others' last block came after them.
    if (count > 1) fleet_step_seconds = std::chrono::duration<double>(Clock::now() - stepping).count();
    for (current = 0; current < count; ++current) rigs[current]->scheduler().stop();
  } catch (const std::exception& e) {
    spdlog::error("{}{}", which(), e.what());
    result.failure = "composed rig: " + which() + e.what();
  }
  if (!progress) {
    result.ok = false;
    result.processes = 1;
    return result;
  }
  for (auto& rig : rigs) rig->close();  // closes the recordings before the summaries read them
  progress->print(true);
  result.launch_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  result.step_seconds = count > 1 ? fleet_step_seconds : progress->stepSeconds();
  result.startup_seconds = progress->startupSeconds(start);
  result.steps = progress->steps();
  result.processes = 1;
  result.ok = result.failure.empty();
  return result;
}

}  // namespace flatsat::rig
