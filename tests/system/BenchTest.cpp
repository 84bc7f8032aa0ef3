// SPDX-License-Identifier: Apache-2.0
// flatsat bench's middleware figures: a truth-state hop between two
// processes and the bare lockstep graph's rate, both over the rig's own bus.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"

using namespace flatsat;

namespace {

using test::kFlatsat;

std::map<std::string, double> keyValues(const std::string& output) {
  std::map<std::string, double> values;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    const auto eq = line.find('=');
    if (eq != std::string::npos) values[line.substr(0, eq)] = std::stod(line.substr(eq + 1));
  }
  return values;
}

}  // namespace

TEST_CASE("bench --middleware measures the hop, the plain graph and the bare lockstep graph", "[system][bench]") {
  const auto result = test::runCommand(kFlatsat + " bench --quick --middleware");
  INFO(result.output);
  REQUIRE(result.exit_code == 0);
  const auto values = keyValues(result.output);
  REQUIRE(values.count("hop_us") == 1);
  REQUIRE(values.count("hop_us_p99") == 1);
  REQUIRE(values.count("limit_steps_per_s") == 1);
  REQUIRE(values.count("plain_graph_steps_per_s") == 1);
  const double hop_us = values.at("hop_us");
  const double limit = values.at("limit_steps_per_s");
  const double plain = values.at("plain_graph_steps_per_s");
  // A loopback hop takes microseconds to milliseconds, never nothing.
  CHECK(hop_us > 1.0);
  CHECK(hop_us < 10'000.0);
  CHECK(values.at("hop_us_p99") >= hop_us);
  CHECK(limit > 0.0);
  // Each step passes master -> sensor -> estimator -> controller -> master in
  // sequence: at least four hops, two here to leave room for a noisy machine.
  CHECK(1e6 / limit > 2.0 * hop_us);
  // The same graph on plain Fast DDS: the same four hops a step, whatever the protocol.
  CHECK(plain > 0.0);
  CHECK(1e6 / plain > 2.0 * hop_us);
}
