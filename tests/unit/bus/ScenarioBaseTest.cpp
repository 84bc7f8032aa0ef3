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
