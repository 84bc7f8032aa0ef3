// SPDX-License-Identifier: Apache-2.0
#include "bus/NodeMain.hpp"
#include "sim/DynamicsServerNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNodeOf<sim::DynamicsServerNode>(
      argc, argv, "dynamics_server",
      [](const bus::Scenario& scenario, const bus::NodeArgs& args, bus::ConfigProblems& problems) {
        return sim::readDynamicsServerParams(scenario, args.name, problems);
      });
}
