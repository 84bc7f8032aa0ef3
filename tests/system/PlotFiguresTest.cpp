// SPDX-License-Identifier: Apache-2.0
// The figures `flatsat run` draws by default (flatsat plot) on runs that
// carry more than the default rig: the MEKF's covariance (3σ bounds around
// the estimation error) and the thruster sequencer's firings.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

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

TEST_CASE("the figures mark faults on the time axis, give every series its own colour, keep legends off the "
          "data and say nothing on stderr",
          "[system][tools][plot]") {
  test::exportTestDomain();
  const std::string run = test::freshDir("plot-events");
  fs::create_directories(run);
  const std::string scenario = run + "/events.yaml";
  std::ofstream(scenario) << "base: " << FLATSAT_SCENARIO_DIR << "/default.yaml\nname: events\n"
                          << "duration_orbits: null\nduration_s: 1800\n"
                          << "spacecraft:\n  faults:\n"
                          << "    - {kind: wheel_degraded, channel: 1, magnitude: 0.5, start_s: 600, duration_s: 300}\n"
                          << "bus_faults:\n  - {kind: drop, topic: flatsat/sun_sensor, magnitude: 0.5, start_s: 300, "
                             "duration_s: 120}\n";
  // stderr alone: a successful run's figures add nothing to it (gnuplot's warnings once did).
  const auto rig = test::runCommand("(" + test::kFlatsat + " run " + scenario + " --composed -q --out " + run +
                                    "/run 2>&1 >/dev/null)");
  INFO(rig.output);
  REQUIRE(rig.exit_code == 0);
  CHECK(rig.output.empty());
  const std::string script = test::readFile(fs::path(run) / "run" / "plots" / "gnuplot" / "plots.gp");
  // 1800 s runs on a minute axis: the faults at 5, 7, 10 and 15 min, on each of the six time figures.
  for (const char* mark : {"set arrow from 5, graph 0", "set arrow from 7, graph 0", "set arrow from 10, graph 0",
                           "set arrow from 15, graph 0"}) {
    CAPTURE(mark);
    std::size_t count = 0;
    for (auto at = script.find(mark); at != std::string::npos; at = script.find(mark, at + 1)) ++count;
    CHECK(count == 6);
  }
  CHECK(script.find("'fault dynamics_server wheel_degraded on'") != std::string::npos);
  CHECK(script.find("'fault bus drop sun_sensor off'") != std::string::npos);
  CHECK(script.find("set linetype 12 lc rgb '#393b79'") != std::string::npos);
  CHECK(script.find("set linetype cycle 12") != std::string::npos);
  CHECK(script.find("key inside") == std::string::npos);
  CHECK(script.find("key outside right") == std::string::npos);

  // A dawn-dusk orbit never enters eclipse: no empty series to plot, no warning.
  const auto detumble = test::runCommand("(" + test::kFlatsat + " run " + std::string(FLATSAT_SCENARIO_DIR) +
                                         "/detumble.yaml --composed -q --out " + run + "/detumble" +
                                         " --set duration_orbits=null --set duration_s=600 2>&1 >/dev/null)");
  INFO(detumble.output);
  CHECK(detumble.exit_code == 0);
  CHECK(detumble.output.empty());
  fs::remove_all(run);
}
