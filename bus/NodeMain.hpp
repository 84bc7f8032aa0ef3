// SPDX-License-Identifier: Apache-2.0
#pragma once
// The body of every component's process (<component>::runProcess, all its
// main() calls): options, scenario, parameters, bus, node, run until done or
// SIGINT/SIGTERM (Fast DDS examples' main).
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <spdlog/spdlog.h>

#include "bus/Bus.hpp"
#include "bus/Node.hpp"
#include "bus/Scenario.hpp"
#include "bus/Shutdown.hpp"

namespace flatsat::bus {

struct NodeArgs {
  std::string scenario;  ///< scenario file
  std::string name;      ///< component name in the scenario
  std::string out_dir;   ///< run directory (recordings, logs)
  bool checkpoint = false;  ///< keep a checkpoint of the state (a run that restarts components)
  bool restarted = false;   ///< started again mid-run: take the state back from its checkpoint
  /// Every process of this rig runs on this host (the launcher started them
  /// all, none under a prefix): a lockstep sink among them reads best-effort
  /// where it shares memory with them (QosTuning::best_effort_readers).
  bool shared_memory_rig = false;
};

/// Parses `--scenario FILE [--name NAME] [--out DIR] [--log LEVEL]`, sets up
/// logging; exits with a usage message on bad arguments.
NodeArgs parseNodeArgs(int argc, char** argv, const std::string& default_name);

/// Everything a node needs from the scenario besides its own parameters.
NodeOptions nodeOptions(const Scenario& scenario, const std::string& name);
/// The same, with the checkpoint a paced process with a run directory keeps when
/// asked (--checkpoint, --restarted: <out>/checkpoints/<name>.json) and whether it
/// restores it (--restarted).
NodeOptions nodeOptions(const Scenario& scenario, const NodeArgs& args);
/// The participant's QoS tuning in this scenario, at the given ownership strength.
QosTuning qosTuning(const Scenario& scenario, std::int32_t ownership_strength);
/// The bus of a component's process: qosTuning(), the network of the
/// environment, and what its arguments say of the rig around it.
BusOptions processBusOptions(const Scenario& scenario, const NodeArgs& args, std::int32_t ownership_strength);

/// Loads the scenario, reads the parameters with `read(scenario, name,
/// problems)`, builds the node with `make(bus, options, params)` and runs it.
/// Returns the process exit code: 0 done, 1 failed, 2 bad configuration.
/// Hardware bridges publish at kBridgeStrength, over their emulators.
template <class Read, class Make>
int runNode(int argc, char** argv, const std::string& default_name, Read&& read, Make&& make,
            std::int32_t ownership_strength = kEmulatorStrength) {
  const NodeArgs args = parseNodeArgs(argc, argv, default_name);
  try {
    installShutdownHandlers();
    const Scenario scenario = loadScenario(args.scenario);
    ConfigProblems problems;
    auto params = read(scenario, args, problems);
    if (!problems.empty()) {
      spdlog::error("{}: invalid parameters:\n{}", args.name, problems.joined());
      return 2;
    }
    Bus bus(processBusOptions(scenario, args, ownership_strength));
    // The node's readers are made, and at the end deleted, while its liveliness
    // watchers are held: one rematch for all of them (Bus::createReader).
    std::optional<Bus::WatchersHeld> held(std::in_place, bus);
    auto node = make(bus, nodeOptions(scenario, args), params);
    held.reset();
    node->run();
    held.emplace(bus);
    return 0;
  } catch (const ScenarioError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const std::exception& e) {
    if (shutdownRequested()) {  // Ctrl-C or SIGTERM: the operator's stop, not a fault of this node
      spdlog::warn("{}: stopped by a signal before the run's end ({})", args.name, e.what());
      return 130;
    }
    spdlog::error("{}: {}", args.name, e.what());
    return 1;
  }
}

/// runNode() of a node built as `NodeType(bus, options, params)`, as every
/// component's is.
template <class NodeType, class Read>
int runNodeOf(int argc, char** argv, const std::string& default_name, Read&& read,
              std::int32_t ownership_strength = kEmulatorStrength) {
  return runNode(
      argc, argv, default_name, std::forward<Read>(read),
      [](Bus& bus, NodeOptions options, const auto& params) {
        return std::make_unique<NodeType>(bus, std::move(options), params);
      },
      ownership_strength);
}

}  // namespace flatsat::bus
