// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/magnetometer_bridge/MagnetometerBridgeNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(
      argc, argv, "magnetometer_bridge", magnetometer_bridge::readParams,
      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
        return std::make_unique<magnetometer_bridge::MagnetometerBridgeNode>(bus, std::move(options), params);
      },
      bus::kBridgeStrength);
}
