// SPDX-License-Identifier: Apache-2.0
// The whole rig against a hostile or broken participant on its bus
// (architecture, "Trust on the bus"; tests/support/hostile_participant.cpp):
// forged stop grants change nothing but the verdict, a process stopped for
// a while is late rather than dead, a NaN burst and absurd
// commands never reach an estimate, a command or the truth, and an intruder
// on a stepped topic ends a lockstep run at once, named. No such run exits 0
// unless every step ran and nobody but the rig wrote to it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/Background.hpp"
#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

using test::kDefault;
// Long enough (a few seconds of stepping) for the 1 s health heartbeats to
// carry the counts into the recording.
const std::string kShort = "--set duration_orbits=null --set duration_s=1200";

/// Every number in a row (nested objects and arrays included) is finite; a NaN
/// or an infinity is exported as null.
bool allFinite(const nlohmann::json& value) {
  if (value.is_null()) return false;
  if (value.is_number()) return std::isfinite(value.get<double>());
  if (value.is_structured()) {
    for (const auto& item : value) {
      if (!allFinite(item)) return false;
    }
  }
  return true;
}

/// Waits until the rig's time master has started stepping.
void waitUntilStepping(const std::string& out, test::Background& rig) {
  REQUIRE(test::waitForText(fs::path(out) / "logs" / "dynamics_server.log", "every component ready", 60, rig));
}

}  // namespace

TEST_CASE("a rig attacked by forged stops, or held up by a stopped process, records what a clean one does",
          "[system][trust]") {
  test::exportTestDomain();
  const auto clean = test::runScenario(kDefault, test::freshDir("trust-clean"), kShort);
  INFO(clean.summary.dump(2));
  CHECK(clean.summary["completed"] == true);
  CHECK(clean.summary["end_reason"] == "completed");
  CHECK(clean.summary["samples_rejected"] == 0);
  CHECK(clean.summary["intruders"] == 0);
  CHECK(clean.summary["commands_clamped"] == 0);

  {  // forged stop grants from another participant are ignored, counted and named; the run is not trusted
    const std::string out = test::freshDir("forged-stop");
    {
      test::Background hostile(test::kHostile + " forge-stop 300 rogue", out + "-hostile.log");
      test::Background rig(test::runLine(kDefault, out, kShort),
                           out + ".log");
      const int code = rig.wait(600);
      INFO(test::readFile(out + ".log"));
      CHECK(code == 1);  // every step ran, but an intruder wrote to the rig
    }
    const auto s = test::readSummary(out);
    INFO(s.dump(2));
    CHECK(s["completed"] == true);
    CHECK(s["steps"] == clean.summary["steps"]);
    CHECK(s["intruders"].get<std::uint64_t>() >= 1);
    CHECK(s["samples_rejected_by_topic"]["flatsat/step_grant"].get<std::uint64_t>() > 0);
    REQUIRE(!s["intruder_writers"].empty());
    CHECK(s["intruder_writers"][0]["participant"] == "rogue");
    CHECK(s["intruder_writers"][0]["topic"] == "flatsat/step_grant");
    // Nothing the rogue sent got in: the recorded run is the clean one.
    CHECK(s["recording_sha256"] == clean.summary["recording_sha256"]);
    fs::remove_all(out);
    fs::remove(out + ".log");
    fs::remove(out + "-hostile.log");
  }

  {  // a component stopped for 5 s is late, not dead: the run completes as the clean one
    const std::string out = test::freshDir("stopped");
    // UDP only: Fast DDS aborts a peer that waits over 1 s on a shared-memory
    // lock a stopped process holds (bus/Bus.hpp, BusNetwork::shared_memory).
    test::Background rig("env FLATSAT_SHARED_MEMORY=0 " + test::runLine(kDefault, out, kShort),
                         out + ".log");
    waitUntilStepping(out, rig);
    const auto pid = test::runCommand("pgrep -n -f '[f]latsat-sun_sensor --scenario " + out + "/'");
    REQUIRE(pid.exit_code == 0);
    std::this_thread::sleep_for(std::chrono::seconds(1));
    REQUIRE(test::runCommand("kill -STOP " + pid.output).exit_code == 0);
    std::this_thread::sleep_for(std::chrono::seconds(5));
    REQUIRE(test::runCommand("kill -CONT " + pid.output).exit_code == 0);
    const int code = rig.wait(600);
    const std::string log = test::readFile(out + ".log");
    INFO(log);
    CHECK(code == 0);
    CHECK(log.find("sun_sensor is late") != std::string::npos);
    const auto s = test::readSummary(out);
    INFO(s.dump(2));
    CHECK(s["completed"] == true);
    CHECK(s["recording_sha256"] == clean.summary["recording_sha256"]);
    const fs::path exported = fs::path(out) / "export";
    REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -t fault_event -o " +
                             exported.string())
                .exit_code == 0);
    bool late = false;
    for (const auto& event : test::exportedRows(exported, "fault_event")) {
      late |= event["kind"] == "late" && event["header"]["source"] == "sun_sensor" && event["active"] == true;
    }
    CHECK(late);
    fs::remove_all(out);
    fs::remove(out + ".log");
  }
}

TEST_CASE("an intruder on a stepped topic stops a lockstep run at once, named, and the summary says so",
          "[system][trust]") {
  test::exportTestDomain();
  const std::string out = test::freshDir("intruder");
  test::Background rig(test::runLine(kDefault, out, "--set duration_orbits=null --set duration_s=100000"),
                       out + ".log");
  waitUntilStepping(out, rig);
  std::this_thread::sleep_for(std::chrono::seconds(2));
  const auto started = std::chrono::steady_clock::now();
  test::Background hostile(test::kHostile + " magnetometer 60 rogue", out + "-hostile.log");
  const int code = rig.wait(120);
  const double stopped_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::string log = test::readFile(out + ".log");
  INFO(log);
  CHECK(code == 1);
  CHECK(stopped_s < 20.0);  // at once: not the 60 s step timeout
  CHECK(log.find("intruder on flatsat/magnetometer") != std::string::npos);
  CHECK(log.find("participant 'rogue'") != std::string::npos);
  const auto s = test::readSummary(out);
  INFO(s.dump(2));
  CHECK(s["completed"] == false);
  CHECK(s["end_reason"].get<std::string>().find("intruder on flatsat/magnetometer") != std::string::npos);
  CHECK(s["intruders"].get<std::uint64_t>() >= 1);
  hostile.signal(SIGTERM);
  hostile.wait(10);
  fs::remove_all(out);
  fs::remove(out + ".log");
  fs::remove(out + "-hostile.log");
}

TEST_CASE("a faulty gyro's NaN burst and a command of 1e300 reach no estimate, command or truth",
          "[system][trust][paced]") {
  test::exportTestDomain();
  const std::string out = test::freshDir("nan-burst");
  {
    test::Background rig(test::runLine(kDefault, out, "--set mode=paced --set duration_orbits=null --set duration_s=25"),
                         out + ".log");
    waitUntilStepping(out, rig);
    std::this_thread::sleep_for(std::chrono::seconds(5));
    // Posing as the rig's own gyro and unloading controller (a device gone bad,
    // not an intruder), over their emulators' ownership strength.
    test::Background nan_gyro(test::kHostile + " nan-gyro 2 gyro", out + "-gyro.log");
    test::Background huge_dipole(test::kHostile + " huge-dipole 2 unloading_controller", out + "-dipole.log");
    CHECK(nan_gyro.wait(30) == 0);
    CHECK(huge_dipole.wait(30) == 0);
    INFO(test::readFile(out + "-gyro.log") + test::readFile(out + "-dipole.log"));
    CHECK(test::readFile(out + "-gyro.log").find("hostile: nan-gyro wrote") != std::string::npos);
    const int code = rig.wait(120);
    INFO(test::readFile(out + ".log"));
    CHECK(code == 0);
  }
  const auto s = test::readSummary(out);
  INFO(s.dump(2));
  CHECK(s["completed"] == true);
  CHECK(s["intruders"] == 0);
  CHECK(s["samples_rejected_by_topic"]["flatsat/gyro"].get<std::uint64_t>() > 0);
  CHECK(s["commands_clamped"].get<std::uint64_t>() > 0);
  const fs::path exported = fs::path(out) / "export";
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out +
                           "/recording.sqlite --json -t attitude_estimate -t wheel_torque_cmd -t dipole_cmd -t truth "
                           "-t gyro -o " + exported.string())
              .exit_code == 0);
  for (const std::string topic : {"attitude_estimate", "wheel_torque_cmd", "dipole_cmd", "truth", "gyro"}) {
    const auto rows = test::exportedRows(exported, topic);
    INFO(topic);
    REQUIRE(rows.size() > 10);  // the dipole command comes at 1 Hz
    std::size_t bad = 0;
    for (const auto& row : rows) bad += !allFinite(row);
    CHECK(bad == 0);
  }
  // The estimate came through the burst: valid again at the end.
  CHECK(test::exportedRows(exported, "attitude_estimate").back()["valid"] == true);
  fs::remove_all(out);
  for (const char* suffix : {".log", "-gyro.log", "-dipole.log"}) fs::remove(out + suffix);
}

TEST_CASE("paced, an intruder on one topic stalls no consumer of the others, and is named",
          "[system][trust][paced]") {
  test::exportTestDomain();
  const std::string out = test::freshDir("paced-intruder");
  {
    test::Background rig(test::runLine(kDefault, out, "--set mode=paced --set duration_orbits=null --set duration_s=25"),
                         out + ".log");
    waitUntilStepping(out, rig);
    std::this_thread::sleep_for(std::chrono::seconds(2));
    // Over the emulator's ownership strength, on a topic the default
    // estimator does not use: its magnetometer samples go nowhere.
    test::Background hostile(test::kHostile + " magnetometer 8 rogue", out + "-hostile.log");
    CHECK(hostile.wait(30) == 0);
    const int code = rig.wait(120);
    INFO(test::readFile(out + ".log"));
    CHECK(code == 1);  // every step ran, but an intruder wrote to the rig
  }
  const auto s = test::readSummary(out);
  INFO(s.dump(2));
  CHECK(s["completed"] == true);
  CHECK(s["intruders"].get<std::uint64_t>() >= 1);
  REQUIRE(!s["intruder_writers"].empty());
  CHECK(s["intruder_writers"][0]["topic"] == "flatsat/magnetometer");
  const fs::path exported = fs::path(out) / "export";
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -t attitude_estimate -o " +
                           exported.string())
              .exit_code == 0);
  const auto rows = test::exportedRows(exported, "attitude_estimate");
  REQUIRE(rows.size() > 100);
  // The estimator went on through the intruder's 8 s (80 steps): no gap near
  // that long, with room for a starved process's late steps.
  std::uint64_t longest_gap = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    longest_gap = std::max(longest_gap, rows[i]["header"]["step"].get<std::uint64_t>() -
                                            rows[i - 1]["header"]["step"].get<std::uint64_t>());
  }
  CHECK(longest_gap < 40);
  fs::remove_all(out);
  fs::remove(out + ".log");
  fs::remove(out + "-hostile.log");
}
