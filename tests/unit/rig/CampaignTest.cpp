// SPDX-License-Identifier: Apache-2.0
// A Monte Carlo campaign's directory: what every run runs, and what is read
// back from it, with processes that stand in for runs.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "rig/Campaign.hpp"

namespace fs = std::filesystem;
using namespace flatsat::rig;

namespace {

Campaign scratchCampaign(const std::string& tag) {
  Campaign c;
  c.dir = (fs::temp_directory_path() / ("flatsat-campaign-" + tag + "-" + std::to_string(::getpid()))).string();
  fs::remove_all(c.dir);
  fs::create_directories(c.dir);
  c.scenario = "deploy/scenarios/default.yaml";
  c.name = "default";
  c.runs = 3;
  c.seed0 = 41;
  c.version = "0.1.0+gtest";
  c.executable = "/bin/sh";
  return c;
}

}  // namespace

TEST_CASE("a campaign reads back as written, and names what is wrong with a damaged one", "[campaign]") {
  const Campaign c = scratchCampaign("io");
  writeCampaign(c);
  const Campaign back = readCampaign(c.dir);
  CHECK(back.dir == c.dir);
  CHECK(back.runs == 3);
  CHECK(back.seed0 == 41);
  CHECK(back.version == c.version);
  CHECK(back.executable == "/bin/sh");
  std::ofstream(fs::path(c.dir) / "campaign.json") << R"({"scenario": "s", "name": "n", "runs": 2})";
  CHECK_THROWS_WITH(readCampaign(c.dir), Catch::Contains("campaign.json: no key 'seed0'"));
  CHECK_THROWS_WITH(readCampaign(c.dir + "-none"), Catch::Contains("cannot read"));
  fs::remove_all(c.dir);
}

TEST_CASE("every run of a campaign is the same command: its resolved scenario, composed, its own seed",
          "[campaign]") {
  const Campaign c = scratchCampaign("args");
  CHECK(runArguments(c, 2) == std::vector<std::string>{"/bin/sh", "run", c.dir + "/scenario.yaml", "--composed",
                                                        "--seed", "43", "--no-plots", "-q", "--out",
                                                        c.dir + "/run-2"});
  fs::remove_all(c.dir);
}

TEST_CASE("a run's end is recorded by whoever waited for it, and gathered from the directory", "[campaign]") {
  Campaign c = scratchCampaign("ends");
  // Stand-ins for `flatsat run`: /bin/sh given "run" as its script cannot
  // open it (POSIX: exit 127; dash, Debian's sh: 2); the test then writes the
  // summary a run would.
  std::vector<StartedRun> running{startRun(c, 0)};
  const auto ended = waitForRun(c, running);
  REQUIRE(ended);
  CHECK(ended->first == 0);
  const int sh_exit = ended->second.exit_code;
  CHECK((sh_exit == 127 || sh_exit == 2));
  CHECK(ended->second.host == hostName());
  CHECK(running.empty());
  const auto status = readRunStatus(c, 0);
  REQUIRE(status);
  CHECK(status->exit_code == sh_exit);

  const auto failed = gatherRun(c, 0);
  CHECK(failed.exit_code == sh_exit);
  CHECK(failed.failure == "exit status " + std::to_string(sh_exit) + " on " + hostName());
  CHECK(failed.log == runLog(c, 0));
  CHECK(gatherRun(c, 1).failure == "no end recorded");
  CHECK(gatherRun(c, 1).exit_code == -1);

  // Run 2 as one that succeeded: status 0 and its summary.
  fs::create_directories(runDirectory(c, 2));
  std::ofstream(fs::path(runDirectory(c, 2)) / "run_status.json")
      << R"({"exit_code": 0, "wall_s": 2.0, "cpu_s": 1.5, "host": "n1"})";
  std::ofstream(fs::path(runDirectory(c, 2)) / "summary.json") << R"({"steps": 10, "recording_sha256": "ab"})";
  std::ofstream(runLog(c, 2)) << "output";
  const auto ok = gatherRun(c, 2);
  CHECK(ok.failure.empty());
  CHECK(ok.summary["steps"] == 10);
  CHECK_FALSE(fs::exists(runLog(c, 2)));  // its run directory keeps its logs
  CHECK(unfinishedRuns(c) == std::vector<int>{0, 1});

  // The campaign's cost: runners' CPU against the runs'.
  fs::create_directories(fs::path(c.dir) / "cost");
  std::ofstream(fs::path(c.dir) / "cost" / "a.json") << R"({"cpu_s": 1.6})";
  std::ofstream(fs::path(c.dir) / "cost" / "b.json") << R"({"cpu_s": 0.4})";
  const double runs_cpu = readRunStatus(c, 0)->cpu_s + 1.5;
  const auto cost = campaignCost(c, {failed, gatherRun(c, 1), ok});
  CHECK(cost["runs_ended"] == 2);
  CHECK(cost["runs_cpu_s"].get<double>() == Approx(runs_cpu));
  CHECK(cost["runners_cpu_s"].get<double>() == Approx(2.0));
  CHECK(cost["overhead_fraction"].get<double>() == Approx((2.0 - runs_cpu) / runs_cpu));
  CHECK(cost["runs_per_cpu_s"].get<double>() == Approx(1 / 2.0));

  clearRun(c, 0);
  CHECK_FALSE(fs::exists(runDirectory(c, 0)));
  CHECK_FALSE(fs::exists(runLog(c, 0)));
  fs::remove_all(c.dir);
}
