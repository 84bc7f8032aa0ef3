// SPDX-License-Identifier: Apache-2.0
// flatsat record and flatsat replay against real rigs: a recording attached
// to a running rig holds the rig's own recorder's samples, and a fresh
// estimator process fed the recorded inputs by the replay (as time master,
// in lockstep) publishes the recorded estimates again, byte for byte.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "tests/support/Background.hpp"
#include "tests/support/RecordingRows.hpp"
#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

using test::kDefault;

/// A finished lockstep run of the default rig; its folder.
std::string finishedRun(const std::string& tag, int duration_s) {
  test::exportTestDomain();
  const std::string dir = test::freshDir(tag);
  const auto run = test::runCommand(test::kFlatsat + " run " + kDefault + " -q --no-plots --out " + dir +
                                    " --set duration_orbits=null --set duration_s=" +
                                    std::to_string(duration_s));
  INFO(run.output);
  REQUIRE(run.exit_code == 0);
  return dir;
}

}  // namespace

TEST_CASE("a replayed recording of the estimator's inputs reproduces its recorded outputs "
          "exactly in lockstep",
          "[recorder][system][tools][replay]") {
  const std::string run = finishedRun("replay", 10);  // steps 0..100
  const std::string rerun = run + "/rerun";
  fs::create_directories(rerun);
  // A fresh estimator with the run's scenario; the replay is its time master
  // and the producer of every recorded topic it does not publish itself.
  // It takes the replay's samples as its producers' (FLATSAT_TRUST): a rig takes none of them.
  test::Background estimator("env FLATSAT_TRUST=flatsat-replay " + std::string(FLATSAT_BIN_DIR) +
                           "/flatsat-estimator --scenario " + run +
                           "/scenario.yaml --name estimator --out " + rerun,
                       rerun + "/estimator.log");
  const auto replay = test::runCommand(test::kFlatsat + " replay " + run +
                                       "/recording.sqlite --wait estimator --capture " + rerun +
                                       "/replay.sqlite --timeout 60");
  INFO(replay.output);
  REQUIRE(replay.exit_code == 0);
  INFO(test::readFile(rerun + "/estimator.log"));
  REQUIRE(estimator.wait(20) == 0);

  for (const std::string topic : {"flatsat/attitude_estimate", "flatsat/field_estimate"}) {
    CAPTURE(topic);
    const auto recorded = test::recordedRows(run + "/recording.sqlite", topic);
    const auto replayed = test::recordedRows(rerun + "/replay.sqlite", topic);
    CHECK(recorded.size() == 101);
    CHECK(replayed.size() == recorded.size());
    std::size_t identical = 0;
    for (const auto& [key, bytes] : recorded) {
      auto it = replayed.find(key);
      identical += it != replayed.end() && it->second == bytes;
    }
    CHECK(identical == recorded.size());
  }
  fs::remove_all(run);
}

TEST_CASE("record attached to a running rig stores the rig's own recorder's samples",
          "[recorder][system][tools][record]") {
  test::exportTestDomain();
  const std::string run = test::freshDir("record-rig");
  const std::string attached = run + "-attached.sqlite";
  fs::remove(attached);
  const std::string log = run + "-record.log";
  test::Background recorder(test::kFlatsat + " record -o " + attached +
                          " -t gyro -t attitude_estimate -t step_grant --seconds 120",
                      log);
  // The tool's participant is up once it says what it records.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (test::readFile(log).find("flatsat record:") == std::string::npos) {
    REQUIRE(std::chrono::steady_clock::now() < deadline);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  // Paced, as a flatsat runs when a tool attaches to it: a lockstep run of
  // this length is over in well under a second, and on a loaded machine the
  // tool's discovery of each component took longer than that (CI: nothing
  // from the gyro, which had exited).
  const auto rig = test::runCommand(test::kFlatsat + " run " + kDefault + " -q --no-plots --out " + run +
                                    " --set mode=paced --set duration_orbits=null --set duration_s=8");
  INFO(rig.output);
  REQUIRE(rig.exit_code == 0);
  // It stops by itself once the rig's stop grant came.
  const int recorded_exit = recorder.wait(30);
  INFO(test::readFile(log));
  REQUIRE(recorded_exit == 0);

  constexpr std::uint64_t kFinalStep = 80;  // 8 s at 0.1 s
  for (const std::string topic : {"flatsat/gyro", "flatsat/attitude_estimate"}) {
    CAPTURE(topic);
    const auto own = test::recordedRows(run + "/recording.sqlite", topic);
    const auto got = test::recordedRows(attached, topic);
    REQUIRE(!own.empty());
    CHECK(own.rbegin()->first.first == kFinalStep);
    // However late the tool matched, it has every sample the rig's own
    // recorder has from its first one on (the writers' 64-step history
    // included: the tool matched within the run's 8 s), each identical.
    REQUIRE(got.size() >= 64);
    const test::TopicRows own_since(own.lower_bound(got.begin()->first), own.end());
    CHECK(got.size() == own_since.size());
    const bool identical = got == own_since;  // (no printing of every payload on failure)
    CHECK(identical);
  }
  fs::remove_all(run);
  // With its WAL's files: SQLite leaves them when a reader closed it last.
  for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(attached + suffix);
  fs::remove(log);
}

TEST_CASE("record refuses an existing file unless --force, and keeps no file when nothing came",
          "[system][tools]") {
  test::exportTestDomain();  // a domain of this test's own, where no rig runs
  const std::string file = test::freshDir("record-force") + ".sqlite";
  const auto nothing = test::runCommand(test::kFlatsat + " record -o " + file + " --seconds 1");
  INFO(nothing.output);
  CHECK(nothing.exit_code == 1);
  CHECK(nothing.output.find("not kept") != std::string::npos);
  CHECK_FALSE(fs::exists(file));
  CHECK_FALSE(fs::exists(file + "-wal"));

  std::ofstream(file) << "an operator's file";
  const auto refused = test::runCommand(test::kFlatsat + " record -o " + file + " --seconds 1");
  INFO(refused.output);
  CHECK(refused.exit_code == 2);
  CHECK(refused.output.find("--force to replace it") != std::string::npos);
  CHECK(test::readFile(file) == "an operator's file");
  const auto forced = test::runCommand(test::kFlatsat + " record -o " + file + " --seconds 1 --force");
  INFO(forced.output);
  CHECK(forced.exit_code == 1);  // replaced, and then nothing came
  CHECK_FALSE(fs::exists(file));
}
