// SPDX-License-Identifier: Apache-2.0
// `flatsat mc`: seeded composed runs, each its own process, J at a time,
// gathered into mc.csv and mc_summary.json.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/types.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/Csv.hpp"
#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

using test::kDefault;
// 300 s with the pointing metrics from 100 s on, so that they see the noise.
const std::string kShort = " --set duration_orbits=null --set duration_s=300 --set metrics.acquisition_s=100";

/// The statistics mc_summary.json promises, computed here from the CSV's column:
/// sample standard deviation, nearest-rank quantiles.
void checkStats(const std::string& key, std::vector<double> v, const nlohmann::json& stats) {
  INFO(key);
  std::sort(v.begin(), v.end());
  const double n = static_cast<double>(v.size());
  double mean = 0;
  for (const double x : v) mean += x / n;
  double var = 0;
  for (const double x : v) var += (x - mean) * (x - mean) / (n - 1);
  auto rank = [&](double q) { return v[static_cast<std::size_t>(std::max(1.0, std::ceil(q * n))) - 1]; };
  CHECK(stats["count"] == v.size());
  CHECK(stats["mean"].get<double>() == Approx(mean).margin(1e-12));
  CHECK(stats["std"].get<double>() == Approx(std::sqrt(var)).margin(1e-12));
  CHECK(stats["min"].get<double>() == v.front());
  CHECK(stats["max"].get<double>() == v.back());
  CHECK(stats["p50"].get<double>() == rank(0.50));
  CHECK(stats["p95"].get<double>() == rank(0.95));
}

/// The pid of a live process whose command line holds every one of `words`; 0 when none.
pid_t findProcess(const std::vector<std::string>& words) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream file(entry.path() / "cmdline");
    std::string cmdline((std::istreambuf_iterator<char>(file)), {});
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    cmdline += ' ';
    if (std::all_of(words.begin(), words.end(),
                    [&](const std::string& w) { return cmdline.find(" " + w + " ") != std::string::npos; })) {
      return static_cast<pid_t>(std::stol(name));
    }
  }
  return 0;
}

}  // namespace

TEST_CASE("flatsat mc runs seeded composed runs in parallel and gathers them into one table",
          "[system][mc]") {
  const std::string out = test::freshDir("mc");
  const auto mc = test::runCommand(test::kFlatsat + " mc " + kDefault +
                                   " --runs 6 --jobs 2 --seed0 7000 --out " + out + kShort);
  INFO(mc.output);
  REQUIRE(mc.exit_code == 0);
  CHECK(mc.output.find("mc: 6/6 runs done, 0 failed") != std::string::npos);

  const test::Csv csv = test::readCsv(fs::path(out) / "mc.csv");
  REQUIRE(csv.rows.size() == 6);
  std::set<std::string> seeds;
  std::set<std::string> digests;
  std::set<std::string> pointing;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const auto& row = csv.rows[i];
    CHECK(row.at("run") == std::to_string(i));
    CHECK(row.at("seed") == std::to_string(7000 + i));
    CHECK(row.at("exit_code") == "0");
    CHECK(row.at("steps") == "3001");
    // Startup (launch to the first step) is part of the run's wall time.
    CHECK(std::stod(row.at("startup_seconds")) > 0.0);
    CHECK(std::stod(row.at("startup_seconds")) < std::stod(row.at("launch_seconds")));
    CHECK(fs::exists(fs::path(out) / ("run-" + std::to_string(i)) / "recording.sqlite"));
    CHECK_FALSE(fs::exists(fs::path(out) / ("run-" + std::to_string(i) + ".log")));  // kept only on failure
    seeds.insert(row.at("seed"));
    digests.insert(row.at("recording_sha256"));
    pointing.insert(row.at("pointing_error_deg_mean"));
  }
  CHECK(seeds.size() == 6);
  // The seed draws the sensors' noise: every run records something else,
  // and the pointing the noisy loop holds differs.
  CHECK(digests.size() == 6);
  CHECK(pointing.size() > 1);

  nlohmann::json summary;
  std::ifstream(fs::path(out) / "mc_summary.json") >> summary;
  CHECK(summary["runs"] == 6);
  CHECK(summary["succeeded"] == 6);
  CHECK(summary["failed"] == 0);
  const auto& metrics = summary["metrics"];
  for (const auto& key : {"pointing_error_deg_mean", "pointing_error_deg_max", "wheel_momentum_Nms_max",
                          "steps"}) {
    REQUIRE(metrics.contains(key));
  }
  for (const auto& [key, stats] : metrics.items()) {
    std::vector<double> column;
    for (const auto& row : csv.rows) column.push_back(std::stod(row.at(key)));
    checkStats(key, column, stats);
  }

  // The same seed again, alone: the identical recording (determinism).
  const std::string again = test::freshDir("mc-again");
  const auto rerun = test::runCommand(test::kFlatsat + " mc " + kDefault + " --runs 1 --seed0 7003 --out " +
                                      again + kShort);
  INFO(rerun.output);
  REQUIRE(rerun.exit_code == 0);
  const test::Csv one = test::readCsv(fs::path(again) / "mc.csv");
  REQUIRE(one.rows.size() == 1);
  CHECK(one.rows[0].at("seed") == "7003");
  CHECK(one.rows[0].at("recording_sha256") == csv.rows[3].at("recording_sha256"));
  CHECK(one.rows[0].at("pointing_error_deg_mean") == csv.rows[3].at("pointing_error_deg_mean"));
  fs::remove_all(out);
  fs::remove_all(again);
}

TEST_CASE("flatsat mc refuses bad input with exit status 2, naming what is wrong", "[system][mc]") {
  const std::string out = test::freshDir("mc-bad");
  struct Case {
    std::string args, says;
  };
  for (const auto& c : {Case{"/nonexistent/scenario.yaml --runs 2", "/nonexistent/scenario.yaml: no such file"},
                        Case{kDefault + " --runs 0", "--runs 0: must be >= 1"},
                        Case{kDefault + " --runs 2 --jobs 0", "--jobs 0: must be >= 1"},
                        Case{kDefault + " --runs 2 --set components.gyro.noise_typo=1", "noise_typo"}}) {
    const auto run = test::runCommand(test::kFlatsat + " mc " + c.args + " --out " + out);
    INFO(run.output);
    CHECK(run.exit_code == 2);
    CHECK(run.output.find(c.says) != std::string::npos);
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("a run that dies is reported with its log and exit status, the others still run, and --resume "
          "runs it again", "[system][mc]") {
  const std::string out = test::freshDir("mc-fail");
  const std::string log = out + ".log";
  const pid_t mc = test::startCommand(test::kFlatsat + " mc " + kDefault + " --runs 3 --jobs 1 --seed0 500 --out " +
                                          out + " --set duration_orbits=null --set duration_s=1000",
                                      log);
  // Run 0 (seed 500) is killed as soon as it shows up.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  pid_t victim = 0;
  while (victim == 0 && std::chrono::steady_clock::now() < deadline) {
    victim = findProcess({"run", "--seed", "500", out + "/run-0"});
    if (victim == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  REQUIRE(victim != 0);
  ::kill(victim, SIGKILL);
  const int exit_code = test::waitCommand(mc);
  const std::string output((std::istreambuf_iterator<char>(std::ifstream(log).rdbuf())), {});
  INFO(output);
  CHECK(exit_code == 1);
  CHECK(output.find("mc: run 0 (seed 500) failed with exit status 137; log " + out + "/run-0.log") !=
        std::string::npos);
  CHECK(fs::exists(fs::path(out) / "run-0.log"));

  const test::Csv csv = test::readCsv(fs::path(out) / "mc.csv");
  REQUIRE(csv.rows.size() == 3);
  CHECK(csv.rows[0].at("exit_code") == "137");
  CHECK(csv.rows[0].at("steps").empty());
  CHECK(csv.rows[1].at("exit_code") == "0");
  CHECK(csv.rows[2].at("exit_code") == "0");
  CHECK(csv.rows[2].at("steps") == "10001");
  nlohmann::json summary;
  std::ifstream(fs::path(out) / "mc_summary.json") >> summary;
  CHECK(summary["succeeded"] == 2);
  CHECK(summary["failed"] == 1);
  CHECK(summary["failed_runs"][0]["seed"] == 500);
  CHECK(summary["failed_runs"][0]["exit_code"] == 137);
  CHECK(summary["metrics"]["steps"]["count"] == 2);

  // --resume runs again only the run that died: the others keep their recordings.
  const auto run2_recording = fs::last_write_time(fs::path(out) / "run-2" / "recording.sqlite");
  const auto resumed = test::runCommand(test::kFlatsat + " mc --resume " + out);
  INFO(resumed.output);
  CHECK(resumed.exit_code == 0);
  CHECK(resumed.output.find("mc: 1 composed runs of 'default'") != std::string::npos);
  CHECK(fs::last_write_time(fs::path(out) / "run-2" / "recording.sqlite") == run2_recording);
  const test::Csv after = test::readCsv(fs::path(out) / "mc.csv");
  REQUIRE(after.rows.size() == 3);
  for (const auto& row : after.rows) {
    CHECK(row.at("exit_code") == "0");
    CHECK(row.at("steps") == "10001");
  }
  CHECK_FALSE(fs::exists(fs::path(out) / "run-0.log"));
  const auto nothing_left = test::runCommand(test::kFlatsat + " mc --resume " + out);
  CHECK(nothing_left.exit_code == 0);
  CHECK(nothing_left.output.find("nothing to resume") != std::string::npos);
  fs::remove_all(out);
  fs::remove(log);
}
