// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/unloading_controller/UnloadingControllerNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "unloading_controller", unloading_controller::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<unloading_controller::UnloadingControllerNode>(bus, std::move(options), params);
                      });
}
