// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

namespace flatsat::analysis {

/// Tick jitter of a paced run as the grants arrived [µs]: each grant's
/// arrival minus its step's place on the period grid, taken from the
/// earliest arrival on that grid (so the hop's constant part drops out).
/// missed: steps up to the last one seen whose grant never arrived.
struct TickJitter {
  double p50_us = 0, p99_us = 0, max_us = 0;
  std::uint64_t ticks = 0, missed = 0;
};

/// What the launcher measured of a run, for its summary (rig::LaunchResult adds how it ended).
struct RunOutcome {
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

}  // namespace flatsat::analysis
