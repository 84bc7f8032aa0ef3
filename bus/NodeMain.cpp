// SPDX-License-Identifier: Apache-2.0
#include "bus/NodeMain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>

#include "bus/Topics.hpp"
#include "flatsat_version.hpp"

namespace flatsat::bus {

NodeArgs parseNodeArgs(int argc, char** argv, const std::string& default_name) {
  NodeArgs args;
  args.name = default_name;
  std::string level = "info";
  CLI::App app{"flatsat component '" + default_name + "'"};
  app.add_option("--scenario", args.scenario, "scenario file (YAML)")->required();
  app.add_option("--name", args.name, "component name in the scenario");
  app.add_option("--out", args.out_dir, "run directory");
  app.add_option("--log", level, "log level: trace, debug, info, warn, error");
  app.add_flag("--checkpoint", args.checkpoint,
               "keep the state in <out>/checkpoints/ after each step (flatsat run --restart)");
  app.add_flag("--restarted", args.restarted,
               "started again mid-run (flatsat run --restart): take the state back from <out>/checkpoints/");
  app.add_flag("--shared-memory-rig", args.shared_memory_rig,
               "every process of this rig runs on this host, started by flatsat run: "
               "lockstep stepped readers go best-effort where they share memory");
  app.set_version_flag("--version", kFlatsatVersion);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    std::exit(app.exit(e));
  } catch (const CLI::ParseError& e) {
    // A usage error exits 2, as the flatsat tool's do, whatever CLI11's own code.
    app.exit(e);
    std::exit(2);
  }
  auto logger = spdlog::stderr_color_mt(args.name);
  logger->set_pattern("[%H:%M:%S.%e] [%n] [%^%l%$] %v");
  spdlog::set_default_logger(logger);
  spdlog::set_level(spdlog::level::from_str(level));
  return args;
}

NodeOptions nodeOptions(const Scenario& scenario, const std::string& name) {
  NodeOptions options;
  options.name = name;
  options.schedule = scenario.schedule();
  options.pacing = scenario.pacing;
  options.period = std::chrono::nanoseconds(std::llround(scenario.step_s * 1e9));
  options.seed = scenario.seed;
  options.bus_faults = scenario.bus_faults;
  for (const auto& component : scenario.components) {
    if (component.role == "bridge") options.bridges.push_back(component.name);
    if (!component.launched) options.externals.push_back(component.name);
  }
  if (const char* trusted = std::getenv("FLATSAT_TRUST")) {
    std::stringstream names(trusted);
    for (std::string participant; std::getline(names, participant, ',');) {
      if (!participant.empty()) options.trusted.push_back(participant);
    }
  }
  return options;
}

NodeOptions nodeOptions(const Scenario& scenario, const NodeArgs& args) {
  NodeOptions options = nodeOptions(scenario, args.name);
  // Only a paced run restarts a component (a lockstep one resumes from its recording).
  if (scenario.pacing == Pacing::kPaced && !args.out_dir.empty() && (args.checkpoint || args.restarted)) {
    const auto folder = std::filesystem::path(args.out_dir) / "checkpoints";
    std::filesystem::create_directories(folder);
    options.checkpoint_file = (folder / (args.name + ".json")).string();
    // A first start never takes a checkpoint left by an earlier run in this folder.
    if (!args.restarted) std::filesystem::remove(options.checkpoint_file);
  }
  options.restarted = args.restarted;
  // The launcher vouches that it started every process of the rig: each
  // takes its grants as every other does (a foreign one, or `flatsat replay`,
  // would wait for a grant a step).
  options.implied_grants = args.shared_memory_rig && scenario.pacing == Pacing::kLockstep;
  return options;
}

QosTuning qosTuning(const Scenario& scenario, std::int32_t ownership_strength) {
  QosTuning tuning;
  tuning.watch_liveliness = scenario.pacing == Pacing::kPaced;
  tuning.lease = std::chrono::milliseconds(std::llround(scenario.liveliness_lease_s * 1e3));
  tuning.ownership_strength = ownership_strength;
  return tuning;
}

BusOptions processBusOptions(const Scenario& scenario, const NodeArgs& args,
                             std::int32_t ownership_strength) {
  BusOptions options{.domain_id = domainFromEnvironment(scenario.domain_id),
                     .participant_name = args.name,
                     .tuning = qosTuning(scenario, ownership_strength),
                     .identity = args.name};
  options.tuning.data_sharing = !args.checkpoint && !args.restarted;  // the launcher may restart it
  useNetwork(options, networkFromEnvironment());
  const bool lockstep = scenario.pacing == Pacing::kLockstep;
  // Shared memory (transport, data sharing and its acknowledgements) speeds a lockstep
  // rig whose every process the launcher owns. One it does not own (role: external) can
  // die holding a shared-memory segment's lock, and Fast DDS 2.9.1 aborts the peers
  // waiting on that lock after its 1 s interprocess timeout: before the 3 s lease names the
  // one that died (seen: a SIGKILLed external wheel_tach took the unloading controller,
  // then, with acknowledgements alone moved to UDP, the dynamics server with it). Such rigs
  // talk UDP alone (on the network profile's interfaces), as a process on another host would anyway.
  const bool any_external = std::any_of(scenario.components.begin(), scenario.components.end(),
                                        [](const ComponentEntry& c) { return !c.launched; });
  // Paced as well: its data sharing and shared-memory transport take the same locks.
  if (any_external) {
    options.shared_memory = false;
    options.tuning.data_sharing = false;
  }
  options.acks_over_shm = lockstep && !any_external;
  // Every writer shares memory with it, and the time master bounds how far a
  // component it schedules may fall behind (bus/StepReports.hpp); DDS Security
  // turns data sharing off (FLATSAT_SECURE_DIR may reach a process the launcher
  // was not told of).
  options.tuning.best_effort_readers = args.shared_memory_rig && lockstep && scenario.schedule().contains(args.name) &&
                                       options.shared_memory && options.tuning.data_sharing &&
                                       options.security_dir.empty();
  if (options.tuning.best_effort_readers) {
    spdlog::info("stepped readers best-effort: a lockstep rig whose every writer shares memory");
  }
  return options;
}

}  // namespace flatsat::bus
