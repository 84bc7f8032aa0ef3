// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/star_tracker/StarTrackerNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "star_tracker", star_tracker::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<star_tracker::StarTrackerNode>(bus, std::move(options), params);
                      });
}
