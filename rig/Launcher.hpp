// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "analysis/RunOutcome.hpp"
#include "bus/Scenario.hpp"

namespace flatsat::rig {

using analysis::TickJitter;

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

/// How a launch ended, with what it measured.
struct LaunchResult : analysis::RunOutcome {
  bool ok = false;
  std::string failure;  ///< which component failed and how
};

/// Starts one process per scenario component, shows progress, and waits
/// for all of them. When one dies, or on SIGINT/SIGTERM, it stops the
/// others (SIGTERM, then SIGKILL) and says which.
LaunchResult launch(const bus::Scenario& scenario, const LaunchOptions& options);

}  // namespace flatsat::rig
