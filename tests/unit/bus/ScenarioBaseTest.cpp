// SPDX-License-Identifier: Apache-2.0
// `base:` in a scenario file: the base's keys with this file's laid over them.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include "bus/Scenario.hpp"

using namespace flatsat::bus;

TEST_CASE("a scenario with a base takes its keys, mappings merged and the rest replaced", "[bus][scenario]") {
  const auto dir = std::filesystem::temp_directory_path() / ("scenario-base-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  };
  write("base.yaml",
        "name: base\nstep_s: 0.5\nduration_s: 10\nseed: 7\n"
        "components:\n  dynamics_server: {substeps: 2, attitude: free}\n  recorder: {}\n"
        "bus_faults:\n  - {kind: drop, topic: flatsat/gyro}\n");
  write("middle.yaml", "base: base.yaml\nname: middle\nseed: 8\n");
  const auto derived = write("derived.yaml",
                             "base: middle.yaml\nname: derived\n"
                             "components:\n  dynamics_server:\n    faults: [{kind: thruster_failed, channel: 1}]\n"
                             "bus_faults: []\n");
  const YAML::Node root = loadScenarioYaml(derived);
  CHECK_FALSE(root["base"]);
  CHECK(root["name"].as<std::string>() == "derived");
  CHECK(root["seed"].as<int>() == 8);             // from the middle, over the base's
  CHECK(root["step_s"].as<double>() == 0.5);      // from the base
  CHECK(root["components"]["dynamics_server"]["substeps"].as<int>() == 2);       // merged mapping keeps the base's
  CHECK(root["components"]["dynamics_server"]["faults"][0]["channel"].as<int>() == 1);  // and adds its own
  CHECK(root["components"]["recorder"]);
  CHECK(root["bus_faults"].size() == 0);          // a list is replaced, not merged
  const Scenario scenario = loadScenario(derived);
  CHECK(scenario.name == "derived");
  CHECK(scenario.seed == 8);

  write("loop_a.yaml", "base: loop_b.yaml\n");
  write("loop_b.yaml", "base: loop_a.yaml\n");
  CHECK_THROWS_WITH(loadScenarioYaml((dir / "loop_a.yaml").string()),
                    Catch::Matchers::Contains("base: the scenario is its own base"));
  write("missing.yaml", "base: nowhere.yaml\n");
  CHECK_THROWS_WITH(loadScenarioYaml((dir / "missing.yaml").string()),
                    Catch::Matchers::Contains("nowhere.yaml: no such file"));
  // An empty base (a bare tag, found by fuzz.scenario) named the folder itself.
  write("bare_tag.yaml", "base: !0");
  CHECK_THROWS_WITH(loadScenarioYaml((dir / "bare_tag.yaml").string()),
                    Catch::Matchers::Contains("base: must be a file name"));
  std::filesystem::create_directories(dir / "folder.yaml");
  write("folder_base.yaml", "base: folder.yaml\n");
  CHECK_THROWS_WITH(loadScenarioYaml((dir / "folder_base.yaml").string()),
                    Catch::Matchers::Contains("folder.yaml: is a directory, not a scenario file"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("a scenario's programs: argv, their bridges, and what is refused with its line", "[bus][scenario]") {
  const auto dir = std::filesystem::temp_directory_path() / ("scenario-programs-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  };
  const std::string rig =
      "name: p\nmode: paced\nduration_s: 10\ncomponents:\n  dynamics_server: {}\n  recorder: {}\n"
      "  attitude_controller_bridge: {role: bridge}\n";
  const Scenario good = loadScenario(write(
      "good.yaml", rig + "programs:\n  - {name: fc, command: [board, --line, \"{run}/a.pty\"], "
                         "bridges: [attitude_controller_bridge]}\n"));
  REQUIRE(good.programs.size() == 1);
  CHECK(good.programs[0].command == std::vector<std::string>{"board", "--line", "{run}/a.pty"});
  CHECK(good.programs[0].bridges == std::vector<std::string>{"attitude_controller_bridge"});

  const std::string bad = write(
      "bad.yaml", rig + "programs:\n"
                        "  - {name: recorder, command: [x]}\n"
                        "  - {name: \"two words\", command: []}\n"
                        "  - {name: fc, command: [x], bridges: [recorder]}\n");
  try {
    loadScenario(bad);
    FAIL("a bad programs list was taken");
  } catch (const ScenarioError& e) {
    const std::string what = e.what();
    INFO(what);
    // Each problem at its own entry's line (lines 9, 10 and 11).
    const auto at = [&](const std::string& line, const std::string& reason) {
      const auto found = what.find(reason);
      return found != std::string::npos && what.rfind(line, found) != std::string::npos &&
             what.rfind(line, found) > what.rfind('\n', found);
    };
    CHECK(at("bad.yaml:9:", "'recorder' is a component's name"));
    CHECK(at("bad.yaml:10:", "'two words' is not a plain word"));
    CHECK(at("bad.yaml:10:", "command: must give the program to run"));
    CHECK(at("bad.yaml:11:", "'recorder' is not a component of this scenario with role: bridge"));
  }
  const std::string lockstep = write("lockstep.yaml", "name: l\nduration_s: 10\ncomponents:\n  dynamics_server: {}\n"
                                                      "programs:\n  - {name: fc, command: [x]}\n");
  CHECK_THROWS_WITH(loadScenario(lockstep), Catch::Matchers::Contains("programs run only beside a paced rig"));
  std::filesystem::remove_all(dir);
}
