// SPDX-License-Identifier: Apache-2.0
// The sensor conformance test, emulator side: every sensor topic of a lockstep
// rig keeps its contract (tests/support/SensorContract.hpp). HilTest checks
// the magnetometer bridge's samples against the same contract.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <filesystem>

#include "tests/support/Rig.hpp"
#include "tests/support/SensorContract.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

/// Runs SCENARIO (lockstep, every component its own process) for 120 s with `extra`
/// settings, exports `topics` and the truth; returns the run directory.
std::string runAndExport(const std::string& tag, const std::string& scenario, const std::string& extra,
                         const std::vector<std::string>& topics) {
  test::exportTestDomain();
  const std::string out = test::freshDir(tag);
  const auto run = test::runCommand(test::kFlatsat + " run " + std::string(FLATSAT_SCENARIO_DIR) + "/" + scenario +
                                    " -q --no-plots --out " + out +
                                    " --set duration_orbits=null --set duration_s=120 " + extra);
  INFO(run.output);
  REQUIRE(run.exit_code == 0);
  std::string wanted = " -t truth";
  for (const auto& topic : topics) wanted += " -t " + topic;
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -o " + out + "/export" +
                           wanted)
              .exit_code == 0);
  return out;
}

std::map<std::uint64_t, nlohmann::json> truthByStep(const std::string& out) {
  std::map<std::uint64_t, nlohmann::json> truth;
  for (auto& row : test::exportedRows(fs::path(out) / "export", "truth")) truth[row["header"]["step"]] = row;
  return truth;
}

}  // namespace

TEST_CASE("every emulated sensor topic keeps its contract", "[system][conformance]") {
  std::vector<std::string> topics;
  for (const auto& [topic, contract] : test::sensorContracts()) {
    if (topic != "star_tracker") topics.push_back(topic);
  }
  const std::string out = runAndExport("conformance", "default.yaml", "", topics);
  const auto truth = truthByStep(out);
  for (const auto& [topic, contract] : test::sensorContracts()) {
    if (topic == "star_tracker") continue;  // the default rig has none: below
    const auto samples = test::exportedRows(fs::path(out) / "export", topic);
    INFO(topic);
    CHECK(samples.size() == 1201);
    const auto breaches = test::contractBreaches(samples, truth, contract, {topic, 0.1, 10.0});
    for (const auto& b : breaches) UNSCOPED_INFO(b);
    CHECK(breaches.empty());
  }
  fs::remove_all(out);
}

TEST_CASE("the star tracker's samples keep their contract", "[system][conformance]") {
  // mekf_star_tracker.yaml: the head's 4 arcsec across the boresight, 30 arcsec about it,
  // no solution within 35 deg of the Sun, 20 deg of the limb or above 2 deg/s (not valid,
  // so not judged on value, but still on header, time and rate).
  const std::string out = runAndExport("conformance-st", "mekf_star_tracker.yaml", "", {"star_tracker"});
  const auto truth = truthByStep(out);
  const auto samples = test::exportedRows(fs::path(out) / "export", "star_tracker");
  CHECK(samples.size() == 1201);
  int valid = 0;
  for (const auto& s : samples) valid += s["valid"].get<bool>() ? 1 : 0;
  CHECK(valid > 1000);  // judged on value, not only on its header
  const auto breaches =
      test::contractBreaches(samples, truth, test::sensorContracts().at("star_tracker"), {"star_tracker", 0.1, 10.0});
  for (const auto& b : breaches) UNSCOPED_INFO(b);
  CHECK(breaches.empty());

  // The checker catches a quaternion in the wrong order (vector part first).
  auto swapped = samples;
  for (auto& s : swapped) {
    auto q = s["q_inertial_body"];
    s["q_inertial_body"] = {q[1], q[2], q[3], q[0]};
  }
  CHECK_FALSE(test::contractBreaches(swapped, truth, test::sensorContracts().at("star_tracker"),
                                     {"star_tracker", 0.1, 10.0})
                  .empty());
  fs::remove_all(out);
}

TEST_CASE("a coarse cosine sun sensor over the bus: each cell gives the cosine of the true Sun",
          "[system][conformance]") {
  // The default rig with the six-cell cube instead of the fine head, no albedo, over DDS.
  const std::string out =
      runAndExport("conformance-css", "default.yaml", "--set components.sun_sensor.type=coarse_cosine", {"sun_sensor"});
  const auto truth = truthByStep(out);
  const auto samples = test::exportedRows(fs::path(out) / "export", "sun_sensor");
  REQUIRE(samples.size() == 1201);
  constexpr double kFiveSigma = 5 * 0.005;  // the default cell noise
  const double normals[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  int off = 0, valid = 0;
  for (const auto& s : samples) {
    REQUIRE(s["cell_count"] == 6);
    const auto& t = truth.at(s["header"]["step"]);
    const double flux = t["solar_flux_W_m2"].get<double>() / 1361.0;
    for (int i = 0; i < 6; ++i) {
      double cosine = 0.0;
      for (int k = 0; k < 3; ++k) cosine += normals[i][k] * t["sun_body_unit"][k].get<double>();
      const double expected = flux * std::max(0.0, cosine);
      if (std::abs(s["cell_output"][i].get<double>() - expected) > kFiveSigma) ++off;
    }
    valid += s["valid"].get<bool>() ? 1 : 0;
  }
  CHECK(off == 0);
  CHECK(valid == 1201);  // the default orbit starts in sunlight
  fs::remove_all(out);
}

TEST_CASE("the sensor contract catches a reading in the wrong unit, a late stamp and a wrong rate",
          "[system][conformance]") {
  // The checker itself, on hand-made samples against a steady truth.
  std::map<std::uint64_t, nlohmann::json> truth;
  std::vector<nlohmann::json> samples;
  for (std::uint64_t k = 0; k < 50; ++k) {
    truth[k] = {{"b_body_T", {2e-5, -1e-5, 3e-5}}};
    samples.push_back({{"header", {{"step", k}, {"sim_time_ns", k * 100'000'000}, {"sample_time_ns", k * 100'000'000},
                                   {"source", "magnetometer"}}},
                       {"b_body_T", {2e-5, -1e-5, 3e-5}},
                       {"valid", true}});
  }
  const auto& contract = test::sensorContracts().at("magnetometer");
  CHECK(test::contractBreaches(samples, truth, contract, {"magnetometer", 0.1, 10.0}).empty());
  auto in_nT = samples;
  in_nT[7]["b_body_T"] = {2e4, -1e4, 3e4};
  // Three components off by orders of magnitude, and the norm out of range.
  CHECK(test::contractBreaches(in_nT, truth, contract, {"magnetometer", 0.1, 10.0}).size() == 4);
  auto late = samples;
  late[9]["header"]["sample_time_ns"] = 1'200'000'000;
  // Stamped after its step, and the next sample's time goes back.
  CHECK(test::contractBreaches(late, truth, contract, {"magnetometer", 0.1, 10.0}).size() == 2);
  CHECK(test::contractBreaches(samples, truth, contract, {"magnetometer", 0.1, 5.0}).size() == 1);
  CHECK(test::contractBreaches(samples, truth, contract, {"magnetometer_bridge", 0.1, 10.0}).size() == 20);
}
