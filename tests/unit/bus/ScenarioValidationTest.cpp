// SPDX-License-Identifier: Apache-2.0
// What `flatsat check` tells a user about a scenario they wrote: each problem
// at its own file, line and column, bounded durations, duplicate keys, and a
// near key suggested for a misspelled one.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include "bus/NearestName.hpp"
#include "bus/Scenario.hpp"
#include "bus/ScenarioPlaces.hpp"

using namespace flatsat::bus;

namespace {

struct ScratchScenarios {
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("scenario-validation-" + std::to_string(::getpid()));
  ScratchScenarios() { std::filesystem::create_directories(dir); }
  ~ScratchScenarios() { std::filesystem::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
};

const char* kMinimal = "components:\n  dynamics_server: {}\n  recorder: {}\n";

/// The message loadScenario throws for `file`, or "" when it loads.
std::string problemsOf(const std::string& file) {
  try {
    loadScenario(file);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("durations are bounded and told at their own line", "[bus][scenario]") {
  const ScratchScenarios s;
  const auto huge_orbits = s.write("a.yaml", std::string("name: a\nduration_orbits: 1e300\n") + kMinimal);
  CHECK_THAT(problemsOf(huge_orbits), Catch::Contains(huge_orbits + ":2:18: duration_orbits: must be in (0, 100000]"));
  const auto huge_time = s.write("b.yaml", std::string("name: b\nduration_s: 1e9\n") + kMinimal);
  CHECK_THAT(problemsOf(huge_time), Catch::Contains(huge_time + ":2:13: duration_s: must be in (0, 3.16e8 s]"));
  const auto negative = s.write("c.yaml", std::string("name: c\nstep_s: 0.1\nduration_s: -100\n") + kMinimal);
  CHECK_THAT(problemsOf(negative), Catch::Contains(negative + ":3:13: duration_s: must be in"));
  // A year of GEO station keeping by the minute is within bounds.
  CHECK(problemsOf(s.write("d.yaml", std::string("name: d\nstep_s: 60\nduration_s: 3.156e7\n") + kMinimal)).empty());
}

TEST_CASE("a base's duration and the user's other one: the hint says how to drop the base's", "[bus][scenario]") {
  const ScratchScenarios s;
  s.write("base.yaml", std::string("name: base\nduration_orbits: 3\n") + kMinimal);
  const auto mine = s.write("mine.yaml", "base: base.yaml\nname: mine\nduration_s: 10\n");
  const std::string problems = problemsOf(mine);
  CHECK_THAT(problems, Catch::Contains(mine + ":3:13: duration_s: give duration_s or duration_orbits, not both"));
  CHECK_THAT(problems, Catch::Contains("duration_orbits: null"));
  CHECK(problemsOf(s.write("fixed.yaml", "base: base.yaml\nname: f\nduration_s: 10\nduration_orbits: null\n")).empty());
}

TEST_CASE("a key written twice in one mapping is refused at its second line", "[bus][scenario]") {
  const ScratchScenarios s;
  const auto twice = s.write("twice.yaml", std::string("name: a\nduration_s: 5\nname: b\n") + kMinimal +
                                               "  recorder: {record_every_steps: 2}\n");
  const std::string problems = problemsOf(twice);
  CHECK_THAT(problems, Catch::Contains(twice + ":3:1: name: duplicate key (first on line 1)"));
  CHECK_THAT(problems, Catch::Contains(twice + ":7:3: components.recorder: duplicate key (first on line 6)"));
}

TEST_CASE("an unknown key is told at its line with the near known key", "[bus][scenario]") {
  const ScratchScenarios s;
  const auto typo = s.write("typo.yaml", std::string("name: a\nduration_s: 5\nstep_ss: 0.1\n") + kMinimal);
  CHECK_THAT(problemsOf(typo), Catch::Contains(typo + ":3:10: step_ss: unknown key (did you mean 'step_s'?)"));
  CHECK(nearestName("gyroo", {"gyro", "recorder"}) == "gyro");
  CHECK(nearestName("stpe_s", {"step_s", "seed"}) == "step_s");  // a swap is one edit
  CHECK_FALSE(nearestName("frobnicate", {"run", "record"}));
}

TEST_CASE("a problem of a key the base writes is placed in the base", "[bus][scenario]") {
  const ScratchScenarios s;
  const auto base = s.write("base.yaml", std::string("name: base\nduration_s: 5\nstep_s: 900\n") + kMinimal);
  const auto mine = s.write("mine.yaml", "base: base.yaml\nname: mine\nseed: 3\nmode: fast\n");
  const std::string problems = problemsOf(mine);
  CHECK_THAT(problems, Catch::Contains(base + ":3:9: step_s: must be in [1 ms, 600 s]"));
  CHECK_THAT(problems, Catch::Contains(mine + ":4:7: mode: 'fast' is not a run mode"));
  CHECK(placeOf(mine, "seed") == "3:7");
  CHECK(placeOf(base, "components.recorder") == "6:13");
  CHECK(placeOf(base, "components.gyro").empty());
}

TEST_CASE("base: names an installed scenario when no file of that name is beside", "[bus][scenario]") {
  const ScratchScenarios s;
  // The unit tests run from build/bin, whose ../share/flatsat/scenarios holds default.yaml.
  const auto mine = s.write("mine.yaml", "base: default\nname: mine\n");
  const Scenario scenario = loadScenario(mine);
  CHECK(scenario.name == "mine");
  REQUIRE(scenario.files.size() == 2);
  CHECK(std::filesystem::path(scenario.files[1]).filename() == "default.yaml");
  CHECK(scenario.hasComponent("unloading_controller"));
}
