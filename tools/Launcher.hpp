// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "bus/Scenario.hpp"

namespace flatsat::tools {

/// Tick jitter of a paced run as the grants arrived [µs]: each grant's
/// arrival minus its step's place on the period grid, taken from the
/// earliest arrival on that grid (so the hop's constant part drops out).
/// missed: steps up to the last one seen whose grant never arrived.
struct TickJitter {
  double p50_us = 0, p99_us = 0, max_us = 0;
  std::uint64_t ticks = 0, missed = 0;
};

struct LaunchOptions {
  std::string bin_dir;        ///< where the flatsat-<component> executables are
  std::string run_dir;        ///< logs go to run_dir/logs/<component>.log
  std::string scenario_file;  ///< the resolved scenario every process reads
  std::string log_level = "info";
  bool progress = true;       ///< live progress line on stderr
  /// component -> command its executable runs under (e.g. `ip netns exec fs-a`,
  /// `ssh box`): the argv words put before the executable and its arguments
  std::map<std::string, std::vector<std::string>> prefixes;
  /// Paced runs: a component that dies (not the dynamics server) is started
  /// again, up to max_restarts times; each restart is recorded as a FaultEvent
  /// (kind "restarted", from the component) and logged to logs/<name>.restart-N.log.
  /// Every component keeps a checkpoint of its state for that (bus/Checkpoint.hpp).
  bool restart = false;
  int max_restarts = 20;  ///< [-] per component and run, >= 1
};

struct LaunchResult {
  bool ok = false;
  std::string failure;          ///< which component failed and how
  double launch_seconds = 0.0;  ///< [s] wall time from spawn to the last exit
  double step_seconds = 0.0;    ///< [s] wall time from the first step to the last (lockstep processes: to the time master's STOPPED health)
  double startup_seconds = 0.0; ///< [s] wall time from launch() to the first step granted
  std::uint64_t steps = 0;      ///< [-] steps granted
  std::size_t processes = 0;
  TickJitter tick_jitter;       ///< paced runs: the grants' arrival jitter at the launcher
  /// [s] for each external component, wall time from the launch to its first health sample
  std::map<std::string, double> external_joined_s;
  /// --restart: how often each component was started again
  std::map<std::string, int> restarts;
};

/// Starts one process per scenario component, shows progress, and waits
/// for all of them. When one dies, or on SIGINT/SIGTERM, it stops the
/// others (SIGTERM, then SIGKILL) and says which.
LaunchResult launch(const bus::Scenario& scenario, const LaunchOptions& options);

}  // namespace flatsat::tools
