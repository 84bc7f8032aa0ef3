// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/magnetometer/MagnetometerNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "magnetometer", magnetometer::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<magnetometer::MagnetometerNode>(bus, std::move(options), params);
                      });
}
