// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/recorder/RecorderNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "recorder", recorder::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<recorder::RecorderNode>(bus, std::move(options), params);
                      });
}
