// SPDX-License-Identifier: Apache-2.0
// Seed S0 over the bus: no magnetometer in the rig; the estimator asks the
// unloading controller for x-dipole windows and estimates the field from the
// wheel momentum; the unloading law runs on that estimate.
#include <catch2/catch.hpp>

#include <sstream>

#include "tests/support/Rig.hpp"

using namespace flatsat;

namespace {
const std::string kS0 = std::string(FLATSAT_SCENARIO_DIR) + "/s0_no_magnetometer.yaml";
}

TEST_CASE("S0 closed loop without a magnetometer keeps the momentum bounded over 5 orbits",
          "[system][slow][s0]") {
  // Composed (ComposedTest: the same recording as the multi-process rig), at the
  // scenario's own 0.1 s frame.
  const auto run = test::runScenario(kS0, test::freshDir("s0"), "--composed");
  const auto& s = run.summary;
  INFO(s.dump(2));
  // The default rig less the magnetometer.
  CHECK(s["roles"].size() == 8);
  CHECK_FALSE(s["roles"].contains("magnetometer"));
  CHECK(s["sim_seconds"].get<double>() >= 5 * 5700);
  // The bound the default rig (with a magnetometer) is held to: 20 % of capacity.
  CHECK(s["wheel_momentum_fraction_max"].get<double>() < 0.2);
  CHECK(s["pointing_error_deg_max"].get<double>() < 0.5);
  // One window every 600 s in sunlight: about 8 an orbit, every one solved.
  CHECK(s["s0_windows_solved"].get<int>() >= 5 * 6);
  CHECK(s["s0_windows_failed"].get<int>() == 0);
  // The estimate the unloading law used, against the truth, all along the run.
  CHECK(s["field_error_pct_rms"].get<double>() < 10.0);
  CHECK(s["alpha_error_deg_rms"].get<double>() < 5.0);
}

TEST_CASE("S0 accuracy at the best setting: field under 5 %, roll under 2 deg",
          "[system][s0]") {
  // flatsat study s0's best row (docs/s0_study.md): 60 s windows, the whole x
  // coil, settle and quiet interval after the pulse; one orbit of the default
  // orbit with the plant's disturbances (gravity gradient, drag, solar pressure).
  const auto result = test::runCommand(
      test::kFlatsat + " study s0 " + kS0 + " --form settle+q --window-s 60 --dipole-Am2 150 --orbits 1");
  INFO(result.output);
  REQUIRE(result.exit_code == 0);
  std::istringstream last(result.output.substr(result.output.rfind("settle+q")));
  std::string form;
  double window = 0, dipole = 0, field_rms = 0, field_max = 0, alpha_rms = 0, alpha_max = 0;
  int cycles = 0, failed = 0;
  last >> form >> window >> dipole >> cycles >> failed >> field_rms >> field_max >> alpha_rms >> alpha_max;
  CHECK(cycles >= 8);
  CHECK(failed == 0);
  CHECK(field_rms < 5.0);
  CHECK(alpha_rms < 2.0);
}
