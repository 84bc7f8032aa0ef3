// SPDX-License-Identifier: Apache-2.0
#pragma once
// Runs of several spacecraft (scenario key spacecraft_count): spacecraft i
// runs the scenario with seed + i on its own bus and records into its own
// directory (rig/ComposedRun.hpp spacecraftDirectory).
#include <string>

#include <nlohmann/json.hpp>

#include "bus/Scenario.hpp"
#include "rig/Launcher.hpp"

namespace flatsat::rig {

/// Every spacecraft as its own multi-process rig on its own DDS domain
/// (the scenario's, FLATSAT_DOMAIN first, + i), all at once: this
/// executable's `run` once per spacecraft, its output into the spacecraft's
/// directory and its log in logs/spacecraft-<i>.log. Fails, naming the
/// spacecraft and its log, when any rig does.
LaunchResult launchFleet(const bus::Scenario& scenario, const LaunchOptions& options);

/// The run's summary.json when it flew several spacecraft: the run's timing
/// (steps_per_second of one spacecraft, spacecraft_steps_per_second of all)
/// and under "spacecraft" each one's summary, which also goes to its directory.
nlohmann::ordered_json fleetSummary(const bus::Scenario& scenario, const std::string& run_dir,
                                    const LaunchResult& result);

}  // namespace flatsat::rig
