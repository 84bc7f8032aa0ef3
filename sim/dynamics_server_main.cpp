// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "bus/NodeMain.hpp"
#include "sim/DynamicsServerNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(
      argc, argv, "dynamics_server",
      [](const bus::Scenario& scenario, const bus::NodeArgs& args, bus::ConfigProblems& problems) {
        return sim::readDynamicsServerParams(scenario, args.name, problems);
      },
      [](bus::Bus& bus, bus::NodeOptions options, const sim::DynamicsServerParams& params) {
        return std::make_unique<sim::DynamicsServerNode>(bus, std::move(options), params);
      });
}
