// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bus/Scenario.hpp"
#include "rig/Launcher.hpp"

namespace flatsat::rig {

/// Why the scenario cannot run composed, one line per component or key
/// ("key: reason"); empty when it can. A composed rig is lockstep,
/// and holds only components that need no DDS peer and no wall clock.
std::vector<std::string> composedProblems(const bus::Scenario& scenario);

/// `flatsat run --composed`: every component of the scenario in this
/// process on one in-process bus (no DDS participant), scheduled in
/// data-flow order on this thread (bus/Composed.hpp). Logs go to
/// run_dir/logs/composed.log; prefixes are not used. The scenario must
/// have no composedProblems().
/// Every spacecraft of the scenario (spacecraft_count) composed on this
/// thread, stepped side by side, each on its own in-process hub.
LaunchResult runComposed(const bus::Scenario& scenario, const LaunchOptions& options);

/// Where spacecraft i records: the run directory itself when it is alone,
/// else its spacecraft-<i> subdirectory.
std::string spacecraftDirectory(const std::string& run_dir, std::uint32_t count, std::uint32_t i);
/// The scenario as spacecraft i runs it: seed + i, domain_id + i.
bus::Scenario spacecraftScenario(const bus::Scenario& scenario, std::uint32_t i);

}  // namespace flatsat::rig
