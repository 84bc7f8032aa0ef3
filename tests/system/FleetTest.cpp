// SPDX-License-Identifier: Apache-2.0
// Several spacecraft in one run (spacecraft_count): each on its own
// bus, so spacecraft i records exactly what a run of the scenario alone with
// seed + i records, composed or as processes on a domain of its own.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

using test::kDefault;
const std::string kShort = "--set duration_orbits=null --set duration_s=60 --set seed=500";

nlohmann::json readJson(const fs::path& file) {
  nlohmann::json j;
  std::ifstream(file) >> j;
  return j;
}

}  // namespace

TEST_CASE("three spacecraft composed record what each records alone, and nothing of the others",
          "[system][composed][fleet]") {
  const std::string out = test::freshDir("fleet-composed");
  const auto fleet = test::runScenario(kDefault, out, kShort + " --set spacecraft_count=3 --composed", true);
  CHECK(fleet.summary["spacecraft_count"] == 3);
  CHECK(fleet.summary["steps"] == 601);
  CHECK(fleet.summary["spacecraft_steps_per_second"].get<double>() ==
        Approx(3 * fleet.summary["steps_per_second"].get<double>()));
  REQUIRE(fleet.summary["spacecraft"].size() == 3);
  for (int i = 0; i < 3; ++i) {
    CAPTURE(i);
    const fs::path dir = fs::path(out) / ("spacecraft-" + std::to_string(i));
    REQUIRE(fs::exists(dir / "recording.sqlite"));
    const auto own = readJson(dir / "summary.json");
    CHECK(own["recording_sha256"] == fleet.summary["spacecraft"][i]["recording_sha256"]);
    // Alone, with the seed the fleet gave it: the same recording to the bit.
    const auto alone = test::runScenario(kDefault, test::freshDir("fleet-alone-" + std::to_string(i)),
                                         "--set duration_orbits=null --set duration_s=60 --composed --set seed=" +
                                             std::to_string(500 + i));
    CHECK(alone.summary["recording_sha256"] == own["recording_sha256"]);
  }
  // Other seeds, other sensor noise: three different recordings.
  CHECK(fleet.summary["spacecraft"][0]["recording_sha256"] != fleet.summary["spacecraft"][1]["recording_sha256"]);
  CHECK(fleet.summary["spacecraft"][1]["recording_sha256"] != fleet.summary["spacecraft"][2]["recording_sha256"]);
  fs::remove_all(out);
}

TEST_CASE("two spacecraft as processes, each rig on its own domain, record what the composed fleet records",
          "[system][fleet]") {
  const auto composed =
      test::runScenario(kDefault, test::freshDir("fleet2-composed"), kShort + " --set spacecraft_count=2 --composed");
  const std::string out = test::freshDir("fleet2-processes");
  const auto processes = test::runScenario(kDefault, out, kShort + " --set spacecraft_count=2", true);
  CHECK(processes.summary["spacecraft_count"] == 2);
  CHECK(processes.summary["processes"] == 2 * 9);  // a default rig is 9 processes
  for (int i = 0; i < 2; ++i) {
    CAPTURE(i);
    CHECK(processes.summary["spacecraft"][i]["recording_sha256"] ==
          composed.summary["spacecraft"][i]["recording_sha256"]);
    CHECK(fs::exists(fs::path(out) / "logs" / ("spacecraft-" + std::to_string(i) + ".log")));
  }
  fs::remove_all(out);
}

TEST_CASE("a spacecraft count out of range, or a fleet with --resume, is refused", "[system][fleet]") {
  const std::string out = test::freshDir("fleet-bad");
  for (const std::string count : {"0", "65"}) {
    const auto run = test::runCommand(test::kFlatsat + " run " + kDefault + " -q --no-plots --composed --out " + out +
                                      " --set spacecraft_count=" + count);
    INFO(run.output);
    CHECK(run.exit_code == 2);
    CHECK(run.output.find("spacecraft_count: must be in 1..64") != std::string::npos);
  }
  const auto restart = test::runCommand(test::kFlatsat + " run " + kDefault + " -q --no-plots --restart --out " +
                                        out + " --set spacecraft_count=2 --set mode=paced");
  INFO(restart.output);
  CHECK(restart.exit_code == 2);
  CHECK(restart.output.find("spacecraft_count 2: --resume, --restart") != std::string::npos);
}
