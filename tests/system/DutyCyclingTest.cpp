// SPDX-License-Identifier: Apache-2.0
// Duty-cycling against magnetometer sampling in the closed loop
// (the magnetometer's torquer coupling and blanking): with the torquers' own field C m
// reaching the magnetometer, the reading holds exactly C m when a coil is on
// at the sample instant, none of the commanded dipole when the unloading
// controller keeps the step's last part quiet, and blanking flags exactly the
// samples taken with a coil on.
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>

#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

constexpr double kCoupling_T_per_Am2 = 3e-8;  // 30 nT per A m² on each coil's own axis
const std::string kCoupling = "3e-8";
const std::string kNoise = "20e-9";  // [T]

struct Samples {
  std::map<std::uint64_t, nlohmann::json> truth, magnetometer;
};

Samples run(const std::string& tag, double quiet_fraction, bool blank) {
  const std::string out = test::freshDir("duty-" + tag);
  const auto result = test::runCommand(
      test::kFlatsat + " run " + std::string(FLATSAT_SCENARIO_DIR) + "/default.yaml --composed -q --no-plots" +
      " --out " + out + " --set duration_orbits=null --set duration_s=300" +
      " --set components.magnetometer.bias_body_T=[0,0,0] --set components.magnetometer.noise_T=" +
      kNoise + " --set components.magnetometer.coil_coupling_T_per_Am2=[" + kCoupling + "," + kCoupling +
      "," + kCoupling + "] --set components.magnetometer.blank_while_coils_on=" +
      (blank ? "true" : "false") + " --set components.unloading_controller.quiet_fraction=" +
      std::to_string(quiet_fraction));
  INFO(result.output);
  REQUIRE(result.exit_code == 0);
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -o " + out +
                           "/export -t truth -t magnetometer")
              .exit_code == 0);
  Samples s;
  for (auto& row : test::exportedRows(fs::path(out) / "export", "truth")) s.truth[row["header"]["step"]] = row;
  for (auto& row : test::exportedRows(fs::path(out) / "export", "magnetometer")) {
    s.magnetometer[row["header"]["step"]] = row;
  }
  fs::remove_all(out);
  return s;
}

/// Least-squares slope (through 0) of the reading's error on C times the
/// dipole named by `dipole_key` in the truth of the same step, over all axes.
double slope(const Samples& s, const std::string& dipole_key, std::size_t& used) {
  double xy = 0.0, xx = 0.0;
  used = 0;
  for (const auto& [k, reading] : s.magnetometer) {
    const auto& truth = s.truth.at(k);
    for (int i = 0; i < 3; ++i) {
      const double x = kCoupling_T_per_Am2 * truth[dipole_key][i].get<double>();
      const double y = reading["b_body_T"][i].get<double>() - truth["b_body_T"][i].get<double>();
      xy += x * y;
      xx += x * x;
    }
    ++used;
  }
  return xy / xx;
}

}  // namespace

TEST_CASE("duty-cycling keeps the torquers' own field out of the magnetometer", "[unloading_controller][system][magnetic][composed]") {
  SECTION("coils on at the sample: the reading holds C m exactly") {
    const auto s = run("on", 0.0, false);
    std::size_t used = 0;
    CHECK(slope(s, "dipole_at_sample_body_Am2", used) == Approx(1.0).margin(0.02));
    CHECK(used == 3001);
  }
  SECTION("coils quiet over the step's last fifth: none of the commanded dipole in the reading") {
    const auto s = run("quiet", 0.2, false);
    std::size_t used = 0;
    // The dipole the plant applied over the step before the sample: on for
    // its first 80 %, off at the sample instant itself.
    CHECK(slope(s, "dipole_body_Am2", used) == Approx(0.0).margin(0.02));
    double applied = 0.0;
    for (const auto& [k, truth] : s.truth) {
      for (int i = 0; i < 3; ++i) {
        CHECK(truth["dipole_at_sample_body_Am2"][i].get<double>() == 0.0);
        applied += std::abs(truth["dipole_body_Am2"][i].get<double>());
      }
    }
    CHECK(applied > 0.0);  // the unloading controller did drive the coils
  }
  SECTION("blanking flags exactly the samples taken with a coil on") {
    for (const double quiet : {0.0, 0.2}) {
      const auto s = run(quiet > 0.0 ? "blank-quiet" : "blank", quiet, true);
      std::size_t blanked = 0, coils_on = 0;
      for (const auto& [k, reading] : s.magnetometer) {
        bool on = false;
        for (int i = 0; i < 3; ++i) on |= s.truth.at(k)["dipole_at_sample_body_Am2"][i].get<double>() != 0.0;
        coils_on += on;
        blanked += !reading["valid"].get<bool>();
        CHECK(reading["valid"].get<bool>() == !on);
      }
      INFO("quiet fraction " << quiet);
      CHECK(blanked == coils_on);
      CHECK((quiet > 0.0 ? coils_on == 0 : coils_on > 1000));
    }
  }
}
