// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/attitude_controller/AttitudeControllerNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "attitude_controller", attitude_controller::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<attitude_controller::AttitudeControllerNode>(bus, std::move(options), params);
                      });
}
