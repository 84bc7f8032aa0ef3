// SPDX-License-Identifier: Apache-2.0
// Momentum dumping by thrusters over the bus: from 90 % of the wheels'
// capacity to under 10 %, the wheels holding the Sun within 1 deg meanwhile.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/support/Run.hpp"
#include "tests/support/TestDomain.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

TEST_CASE("thruster couples dump wheel momentum from 90 % to under 10 % of capacity within 1 deg pointing",
          "[thruster_sequencer][system][dumping]") {
  test::exportTestDomain();
  const fs::path out = fs::temp_directory_path() / ("flatsat-test-dumping-" + std::to_string(::getpid()));
  fs::remove_all(out);
  const auto command = test::runCommand(std::string(FLATSAT_BIN_DIR) + "/flatsat run " +
                                        std::string(FLATSAT_SCENARIO_DIR) +
                                        "/thruster_dumping.yaml --composed -q --no-plots --out " +
                                        out.string());
  INFO(command.output);
  REQUIRE(command.exit_code == 0);
  nlohmann::json s;
  std::ifstream(out / "summary.json") >> s;
  fs::remove_all(out);
  INFO(s.dump(2));
  const double capacity = s["wheel_capacity_Nms"].get<double>();
  CHECK(s["wheel_momentum_Nms_start"].get<double>() >= 0.89 * capacity);
  CHECK(s["wheel_momentum_Nms_end"].get<double>() < 0.1 * capacity);
  CHECK(s["pointing_error_deg_max"].get<double>() < 1.0);
  // Angle-only figures belong to the S1 mode only.
  CHECK_FALSE(s.contains("correction_counts"));
}
