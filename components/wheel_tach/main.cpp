// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/wheel_tach/WheelTachNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "wheel_tach", wheel_tach::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<wheel_tach::WheelTachNode>(bus, std::move(options), params);
                      });
}
