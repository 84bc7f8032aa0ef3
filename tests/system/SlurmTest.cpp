// SPDX-License-Identifier: Apache-2.0
// `flatsat mc --slurm` against a real Slurm: Debian's munged, slurmctld and
// slurmd started on this host (deploy/slurm/local-cluster.sh, loopback only),
// sbatch, squeue and scancel as users type them.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/Csv.hpp"
#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

const std::string kClusterScript = std::string(FLATSAT_SOURCE_DIR) + "/deploy/slurm/local-cluster.sh";
const std::string kOneOrbit = " --set duration_orbits=1";

/// The single-node cluster of this test, stopped (and its files removed) at the end.
struct LocalSlurm {
  std::string dir = test::freshDir("slurm-cluster");
  bool up = false;
  std::string why;
  LocalSlurm() {
    // Ports of this test process's own: a cluster of another run cannot answer.
    const int port = 20000 + static_cast<int>(::getpid() % 10000) * 2;
    const auto start = test::runCommand("bash " + kClusterScript + " start " + dir + " " + std::to_string(port));
    up = start.exit_code == 0;
    why = start.output;
    if (up) ::setenv("SLURM_CONF", (dir + "/slurm.conf").c_str(), 1);
  }
  ~LocalSlurm() {
    ::unsetenv("SLURM_CONF");
    test::runCommand("bash " + kClusterScript + " stop " + dir);
  }
};

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

nlohmann::json readJsonFile(const fs::path& file) {
  nlohmann::json j;
  std::ifstream(file) >> j;
  return j;
}

}  // namespace

TEST_CASE("flatsat mc --slurm runs a campaign as a job array: the local campaign's runs, a cancelled task "
          "reported and resumed",
          "[system][mc][slurm][all_cores]") {
  LocalSlurm slurm;
  if (!slurm.up) {
    WARN("SKIPPED: the Slurm daemons cannot start here: " << slurm.why);
    return;
  }
  const std::string out = test::freshDir("mc-slurm");
  const std::string mc = test::kFlatsat + " mc " + test::kDefault + " --runs 40 --slurm --per-task 5 --out " + out;

  SECTION("bad options are refused before anything is submitted") {
    struct Case {
      std::string command, says;
    };
    for (const auto& c : {Case{"env PATH=/nonexistent " + mc, "sbatch is not on PATH"},
                          Case{mc + " --partition nosuch", "--partition nosuch: no such partition (this cluster "
                                                           "has: flatsat)"},
                          Case{mc + " --time 1h", "--time 1h: not a Slurm time limit"},
                          Case{test::kFlatsat + " mc " + test::kDefault + " --runs 2000 --slurm --out " + out,
                               "2000 array tasks exceed this cluster's MaxArraySize 1001"},
                          Case{test::kFlatsat + " mc " + test::kDefault + " --runs 4 --slurm --per-task 0 --out " + out,
                               "--per-task 0: must be >= 1"},
                          Case{test::kFlatsat + " mc " + test::kDefault + " --runs 4 --per-task 2 --out " + out,
                               "go with --slurm"}}) {
      const auto run = test::runCommand(c.command);
      INFO(c.command << "\n" << run.output);
      CHECK(run.exit_code == 2);
      CHECK(run.output.find(c.says) != std::string::npos);
      CHECK_FALSE(fs::exists(out));
    }
    CHECK(trimmed(test::runCommand("squeue -h -o %i").output).empty());
  }

  SECTION("the same runs as locally; a cancelled task's runs reported, then resumed") {
    const auto submit = test::runCommand(mc + " --no-wait" + kOneOrbit);
    INFO(submit.output);
    REQUIRE(submit.exit_code == 0);
    // --no-wait prints the job id last, on stdout.
    const std::string job = trimmed(submit.output.substr(trimmed(submit.output).rfind('\n') + 1));
    REQUIRE(job.find_first_not_of("0123456789") == std::string::npos);
    CHECK(fs::exists(fs::path(out) / "slurm" / "submission-1.sh"));

    // Array task 0 is cancelled once its first run has ended: its run in
    // progress is stopped and the rest never start.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(fs::path(out) / "run-0" / "run_status.json") && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    REQUIRE(test::runCommand("scancel " + job + "_0").exit_code == 0);

    const auto collected = test::runCommand(test::kFlatsat + " mc --collect " + out);
    INFO(collected.output);
    CHECK(collected.exit_code == 1);
    const test::Csv first = test::readCsv(fs::path(out) / "mc.csv");
    REQUIRE(first.rows.size() == 40);
    CHECK(first.rows[0].at("exit_code") == "0");
    int failed = 0;
    for (std::size_t i = 0; i < first.rows.size(); ++i) {
      const bool ok = first.rows[i].at("exit_code") == "0" && !first.rows[i].at("recording_sha256").empty();
      if (i >= 5) CHECK(ok);  // the other tasks ran to their end
      failed += ok ? 0 : 1;
    }
    CHECK(failed >= 1);
    const auto summary = readJsonFile(fs::path(out) / "mc_summary.json");
    CHECK(summary["failed"] == failed);
    REQUIRE(summary["failed_runs"].size() == static_cast<std::size_t>(failed));
    for (const auto& run : summary["failed_runs"]) {
      INFO(run.dump());
      CHECK(run["run"].get<int>() >= 1);
      CHECK(run["run"].get<int>() <= 4);
      CHECK(run["reason"].get<std::string>().find("array task 0 of job " + job + ": cancelled on localhost") !=
            std::string::npos);
    }
    CHECK(collected.output.find("array task 0 of job " + job + ": cancelled") != std::string::npos);

    const auto resumed = test::runCommand(test::kFlatsat + " mc --resume " + out + " --slurm --per-task 5");
    INFO(resumed.output);
    REQUIRE(resumed.exit_code == 0);
    // Only the missing runs went to Slurm again.
    const auto second = readJsonFile(fs::path(out) / "slurm" / "submission-2.json");
    std::set<int> resubmitted;
    for (const auto& task : second["tasks"]) {
      for (const auto& run : task) resubmitted.insert(run.get<int>());
    }
    CHECK(resubmitted.size() == static_cast<std::size_t>(failed));
    CHECK(*resubmitted.begin() >= 1);
    CHECK(*resubmitted.rbegin() <= 4);
    const test::Csv slurm_runs = test::readCsv(fs::path(out) / "mc.csv");
    REQUIRE(slurm_runs.rows.size() == 40);
    const auto slurm_summary = readJsonFile(fs::path(out) / "mc_summary.json");
    CHECK(slurm_summary["succeeded"] == 40);
    CHECK(slurm_summary["cost"]["runs_per_cpu_s"].get<double>() > 0);
    CHECK(slurm_summary["slurm_jobs"].size() == 2);

    // The same campaign on this host: run by run the same recording.
    const std::string local = test::freshDir("mc-slurm-local");
    const auto here = test::runCommand(test::kFlatsat + " mc " + test::kDefault + " --runs 40 --jobs 2 --out " +
                                       local + kOneOrbit);
    INFO(here.output);
    REQUIRE(here.exit_code == 0);
    const test::Csv local_runs = test::readCsv(fs::path(local) / "mc.csv");
    REQUIRE(local_runs.rows.size() == 40);
    std::set<std::string> digests;
    for (std::size_t i = 0; i < 40; ++i) {
      INFO("run " << i);
      for (const char* key : {"run", "seed", "exit_code", "recording_sha256", "steps", "pointing_error_deg_mean",
                              "wheel_momentum_Nms_max"}) {
        CHECK(slurm_runs.rows[i].at(key) == local_runs.rows[i].at(key));
      }
      digests.insert(local_runs.rows[i].at("recording_sha256"));
    }
    CHECK(digests.size() == 40);  // every seed its own run
    fs::remove_all(local);
  }
  fs::remove_all(out);
}
