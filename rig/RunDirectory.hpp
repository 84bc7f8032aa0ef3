// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <string>
#include <vector>

namespace flatsat::rig {

/// Writes DIR/scenario.yaml: the scenario file with `key.path=value`
/// overrides applied, so that every process of the run reads exactly the
/// same configuration and the run directory documents it. Returns its path.
/// Throws std::invalid_argument naming a malformed override.
std::string writeRunScenario(const std::string& scenario_file, const std::string& run_dir,
                             const std::vector<std::string>& overrides);

/// A problem found in a scenario that writeRunScenario() resolved, told in
/// the user's terms: "<resolved>:L:C: key: reason" becomes "--set k=v: key:
/// reason" when the key (or a parent of it) came from an override, else
/// "<scenario_file>:L:C: key: reason" at the key's place in that file when it
/// is there. Anything else is returned as it is.
std::string attributeProblem(const std::string& problem, const std::string& resolved,
                             const std::string& scenario_file, const std::vector<std::string>& overrides);

/// The override that records one step per simulated second at base period
/// step_s, as 42 writes its output files (every step when step_s >= 1 s).
/// The recorder's transactions then hold 50 recorded steps by default.
std::string recordOnceASecond(double step_s);

/// runs/<scenario name>-<UTC timestamp> under the current directory.
std::string defaultRunDirectory(const std::string& scenario_name);

}  // namespace flatsat::rig
