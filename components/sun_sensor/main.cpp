// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/sun_sensor/SunSensorNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "sun_sensor", sun_sensor::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<sun_sensor::SunSensorNode>(bus, std::move(options), params);
                      });
}
