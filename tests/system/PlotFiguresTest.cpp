// SPDX-License-Identifier: Apache-2.0
// The figures `flatsat run` draws by default (flatsat plot) on runs that
// carry more than the default rig: the MEKF's covariance (3σ bounds around
// the estimation error) and the thruster sequencer's firings.
#include <catch2/catch.hpp>

#include <filesystem>

#include "tests/support/Background.hpp"
#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

/// Runs `scenario` for `duration_s`; the run's plot folder.
fs::path plotted(const std::string& scenario, const std::string& tag, int duration_s) {
  test::exportTestDomain();
  const std::string run = test::freshDir(tag);
  const auto rig = test::runCommand(test::kFlatsat + " run " + std::string(FLATSAT_SCENARIO_DIR) +
                                    "/" + scenario + " -q --out " + run +
                                    " --set duration_orbits=null --set duration_s=" +
                                    std::to_string(duration_s));
  INFO(rig.output);
  REQUIRE(rig.exit_code == 0);
  return fs::path(run) / "plots";
}

bool isPng(const fs::path& png) {
  return fs::exists(png) && fs::file_size(png) > 10000 &&
         test::readFile(png).rfind("\x89PNG\r\n\x1a\n", 0) == 0;
}

}  // namespace

TEST_CASE("run draws the figures by default: the filter's 3-sigma bounds around the "
          "estimation error and the thruster firings",
          "[system][tools][plot]") {
  const fs::path mekf = plotted("mekf.yaml", "plot-mekf", 60);
  CHECK(isPng(mekf / "estimator_error.png"));
  const std::string mekf_script = test::readFile(mekf / "gnuplot" / "plots.gp");
  CHECK(mekf_script.find("+3σ (covariance)") != std::string::npos);
  CHECK(!fs::exists(mekf / "thrusters.png"));  // no sequencer in that rig
  fs::remove_all(mekf.parent_path());

  const fs::path thrusters = plotted("thruster_dumping.yaml", "plot-thrusters", 30);
  CHECK(isPng(thrusters / "thrusters.png"));
  const std::string script = test::readFile(thrusters / "gnuplot" / "plots.gp");
  CHECK(script.find("'thruster 1'") != std::string::npos);
  // A firing step per data row: every step of the dumping fires (30 s at 0.1 s).
  const std::string data = test::readFile(thrusters / "gnuplot" / "thruster.dat");
  CHECK(std::count(data.begin(), data.end(), '\n') > 100);
  fs::remove_all(thrusters.parent_path());
}
