// SPDX-License-Identifier: Apache-2.0
#include <memory>

#include "components/estimator/EstimatorNode.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  return bus::runNode(argc, argv, "estimator", estimator::readParams,
                      [](bus::Bus& bus, bus::NodeOptions options, const auto& params) {
                        return std::make_unique<estimator::EstimatorNode>(bus, std::move(options), params);
                      });
}
