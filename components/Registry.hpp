// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "bus/NodeMain.hpp"

namespace flatsat {

/// A kind of component the launcher can start.
struct ComponentKind {
  std::string name;        ///< as listed under components: in a scenario
  std::string executable;  ///< flatsat-<name>, next to the flatsat tool
  /// Reads the component's parameters, reporting every problem.
  std::function<void(const bus::Scenario&, const bus::NodeArgs&, bus::ConfigProblems&)> check;
};

const std::vector<ComponentKind>& componentKinds();
const ComponentKind* findComponentKind(const std::string& name);

/// Every problem of a scenario: the top level (loadScenario), each listed
/// component's parameters, unknown component names and a missing time
/// master or recorder. Empty when the rig can start.
std::vector<std::string> checkScenario(const bus::Scenario& scenario, const std::string& out_dir);

}  // namespace flatsat
