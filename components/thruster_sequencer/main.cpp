// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/thruster_sequencer/ThrusterSequencerNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "thruster_sequencer", thruster_sequencer::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<thruster_sequencer::ThrusterSequencerNode>(bus, std::move(options), params);
                      });
}
