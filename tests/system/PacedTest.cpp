// SPDX-License-Identifier: Apache-2.0
// Paced mode: the dynamics server follows the wall clock and waits for
// nobody; the rig keeps up at the default rates on this machine.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/support/Run.hpp"
#include "tests/support/TestDomain.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

TEST_CASE("a paced run follows the wall clock and applies the newest commands", "[system][paced]") {
  test::exportTestDomain();
  const std::string out =
      (fs::temp_directory_path() / ("flatsat-test-paced-" + std::to_string(::getpid()))).string();
  fs::remove_all(out);
  const auto result = test::runCommand(
      std::string(FLATSAT_BIN_DIR) + "/flatsat run " + FLATSAT_SCENARIO_DIR +
      "/default.yaml -q --out " + out +
      " --set mode=paced --set duration_orbits=null --set duration_s=20");
  INFO(result.output);
  REQUIRE(result.exit_code == 0);
  nlohmann::json summary;
  std::ifstream(fs::path(out) / "summary.json") >> summary;
  INFO(summary.dump(2));
  CHECK(summary["mode"] == "paced");
  CHECK(summary["steps"] == 201);
  // 20 s of simulated time took about 20 s of wall time.
  CHECK(summary["speed_factor"].get<double>() == Approx(1.0).epsilon(0.05));
  // The newest command is applied: rarely late on a quiet machine, never
  // wildly so; the counts are reported whatever they are.
  CHECK(summary["wheel_commands_late"].get<int>() < 20);
  CHECK(summary.contains("stale_inputs"));
  CHECK(summary.contains("overruns"));
  // Every grant reached the launcher, each on the period grid to within a
  // fraction of the period (the jitter is measured from the earliest).
  CHECK(summary["ticks_missed"] == 0);
  CHECK(summary["tick_jitter_us_p50"].get<double>() >= 0.0);
  CHECK(summary["tick_jitter_us_p50"].get<double>() <= summary["tick_jitter_us_p99"].get<double>());
  CHECK(summary["tick_jitter_us_p99"].get<double>() <= summary["tick_jitter_us_max"].get<double>());
  CHECK(summary["tick_jitter_us_p99"].get<double>() < 0.5 * 0.1e6);
  fs::remove_all(out);
}
