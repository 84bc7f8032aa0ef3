// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/gyro/GyroNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "gyro", gyro::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<gyro::GyroNode>(bus, std::move(options), params);
                      });
}
