// SPDX-License-Identifier: Apache-2.0
// Bus faults from the scenario (bus_faults:) in the closed loop: samples of a
// topic dropped, delayed or duplicated on their way to the consumers. The
// recording keeps every sample the producers wrote, says which one the
// consumers held at each faulted step (flatsat/bus_delivery), and has a
// FaultEvent at each start and end; the consumers react as a flight unit
// would (a lost Sun sample is no Sun correction, a late command is applied
// late). The multi-process rig and the composed one record the same bits.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

// Windows in steps of 0.1 s.
constexpr std::uint64_t kSunLostFrom = 100, kSunLostTo = 130;       // every Sun sample lost
constexpr std::uint64_t kLateFrom = 200, kLateTo = 250, kLate = 5;   // wheel commands 0.5 s late
constexpr std::uint64_t kFieldFrom = 300, kFieldTo = 400;           // 30 % of the field samples lost
constexpr std::uint64_t kTwiceFrom = 50, kTwiceTo = 100;            // every gyro sample written twice
const std::string kFaults =
    "bus_faults=["
    "{kind: drop, topic: flatsat/sun_sensor, start_s: 10, duration_s: 3},"
    "{kind: delay, topic: flatsat/wheel_torque_cmd, magnitude: 0.5, start_s: 20, duration_s: 5},"
    "{kind: drop, topic: flatsat/magnetometer, magnitude: 0.3, start_s: 30, duration_s: 10},"
    "{kind: duplicate, topic: flatsat/gyro, start_s: 5, duration_s: 5}]";

std::map<std::uint64_t, nlohmann::json> byStep(const fs::path& dir, const std::string& topic) {
  std::map<std::uint64_t, nlohmann::json> rows;
  for (auto& row : test::exportedRows(dir, topic)) rows[row["header"]["step"]] = row;
  return rows;
}

}  // namespace

TEST_CASE("bus faults drop, delay and duplicate samples as defined, recorded, the same composed",
          "[system][faults][bus_faults]") {
  const std::string args = "--set duration_orbits=null --set duration_s=60 --set '" + kFaults + "'";
  const std::string scenario = std::string(FLATSAT_SCENARIO_DIR) + "/default.yaml";
  const std::string out = test::freshDir("bus-faults");
  const auto processes = test::runScenario(scenario, out, args, true);
  const auto composed = test::runScenario(scenario, test::freshDir("bus-faults-composed"), args + " --composed");
  CHECK(composed.summary["recording_sha256"] == processes.summary["recording_sha256"]);

  const fs::path dir = fs::path(out) / "export";
  const auto exporting = test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -o " +
                                          dir.string() +
                                          " -t bus_delivery -t fault_event -t attitude_estimate -t truth"
                                          " -t sun_sensor -t magnetometer -t gyro -t health");
  INFO(exporting.output);
  REQUIRE(exporting.exit_code == 0);

  // Nothing a producer wrote is missing from the recording, lost or not.
  for (const std::string topic : {"sun_sensor", "magnetometer", "gyro"}) {
    CAPTURE(topic);
    CHECK(byStep(dir, topic).size() == 601);
  }

  std::map<std::string, std::map<std::uint64_t, nlohmann::json>> delivered;  // by topic, step
  for (auto& row : test::exportedRows(dir, "bus_delivery")) {
    delivered[row["topic"].get<std::string>()][row["header"]["step"]] = row;
  }

  // The Sun outage: at each step of it the estimator holds the last sample
  // before it, and does not correct with it; before and after, it does.
  const auto& sun = delivered["flatsat/sun_sensor"];
  CHECK(sun.size() == kSunLostTo - kSunLostFrom);
  const auto estimate = byStep(dir, "attitude_estimate");
  for (std::uint64_t k = kSunLostFrom - 5; k < kSunLostTo + 5; ++k) {
    CAPTURE(k);
    const bool lost = k >= kSunLostFrom && k < kSunLostTo;
    CHECK(estimate.at(k)["sun_used"] == !lost);
    if (lost) {
      CHECK(sun.at(k)["sample_step"] == kSunLostFrom - 1);
      CHECK(sun.at(k)["dropped"] == true);
    } else {
      CHECK(sun.count(k) == 0);
    }
  }

  // Late wheel commands: truth k + 1 carries the age of the command the plant
  // held over [t_k, t_k+1): growing to the delay at the window's start, then
  // the delay, then back to 0 when commands are on time again.
  const auto truth = byStep(dir, "truth");
  for (std::uint64_t k = kLateFrom - 5; k < kLateTo + 5; ++k) {
    CAPTURE(k);
    const std::int64_t expected =
        k < kLateFrom || k >= kLateTo ? 0 : static_cast<std::int64_t>(std::min(k - (kLateFrom - 1), kLate));
    CHECK(truth.at(k + 1)["wheel_cmd_age_steps"].get<std::int64_t>() == expected);
  }
  CHECK(delivered["flatsat/wheel_torque_cmd"].at(kLateFrom + 10)["delay_steps"] == kLate);

  // A partial drop of the field: 30 % of the window's 100 samples (binomial:
  // 4 sigma = 18), each lost one replaced by the newest sample that was not.
  const auto& field = delivered["flatsat/magnetometer"];
  REQUIRE(field.size() == kFieldTo - kFieldFrom);
  int lost = 0;
  for (const auto& [k, row] : field) {
    CAPTURE(k);
    const bool dropped = row["dropped"].get<bool>();
    lost += dropped;
    const auto held = row["sample_step"].get<std::uint64_t>();
    CHECK((dropped ? held < k : held == k));
    for (std::uint64_t s = held + 1; s <= k && s >= kFieldFrom; ++s) CHECK(field.at(s)["dropped"] == true);
  }
  CHECK(std::abs(lost - 30) <= 18);

  // Duplicates reach every gyro reader twice and are passed on once: the
  // estimator and the recorder each dropped the 50 copies (and any sample
  // written again after a stall, bus::kResendAfter, which a loaded machine
  // can cause).
  CHECK(delivered["flatsat/gyro"].size() == kTwiceTo - kTwiceFrom);
  std::map<std::string, std::uint64_t> copies;
  for (const auto& health : test::exportedRows(dir, "health")) {
    copies[health["header"]["source"].get<std::string>()] = health["copies_dropped"].get<std::uint64_t>();
  }
  CHECK(copies["estimator"] >= kTwiceTo - kTwiceFrom);
  CHECK(copies["recorder"] >= kTwiceTo - kTwiceFrom);

  // Every start and end, at its step, from the bus.
  std::set<std::tuple<std::string, std::string, std::uint64_t, bool>> events;
  for (const auto& event : test::exportedRows(dir, "fault_event")) {
    CHECK(event["header"]["source"] == "bus");
    events.insert({event["topic"].get<std::string>(), event["kind"].get<std::string>(),
                   event["header"]["step"].get<std::uint64_t>(), event["active"].get<bool>()});
  }
  const std::set<std::tuple<std::string, std::string, std::uint64_t, bool>> expected_events = {
      {"flatsat/sun_sensor", "drop", kSunLostFrom, true},        {"flatsat/sun_sensor", "drop", kSunLostTo, false},
      {"flatsat/wheel_torque_cmd", "delay", kLateFrom, true},    {"flatsat/wheel_torque_cmd", "delay", kLateTo, false},
      {"flatsat/magnetometer", "drop", kFieldFrom, true},        {"flatsat/magnetometer", "drop", kFieldTo, false},
      {"flatsat/gyro", "duplicate", kTwiceFrom, true},           {"flatsat/gyro", "duplicate", kTwiceTo, false}};
  CHECK(events == expected_events);
  fs::remove_all(out);
}
