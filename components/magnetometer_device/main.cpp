// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/magnetometer_device/MagnetometerDeviceNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "magnetometer_device", magnetometer_device::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<magnetometer_device::MagnetometerDeviceNode>(
                            bus, std::move(options), params);
                      });
}
