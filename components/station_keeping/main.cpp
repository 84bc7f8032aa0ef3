// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/station_keeping/StationKeepingNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "station_keeping", station_keeping::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<station_keeping::StationKeepingNode>(bus, std::move(options), params);
                      });
}
