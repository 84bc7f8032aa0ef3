// SPDX-License-Identifier: Apache-2.0
#include "rig/RunDirectory.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include "bus/Scenario.hpp"
#include "bus/ScenarioPlaces.hpp"

namespace flatsat::rig {

namespace fs = std::filesystem;

std::string writeRunScenario(const std::string& scenario_file, const std::string& run_dir,
                             const std::vector<std::string>& overrides) {
  YAML::Node root = bus::loadScenarioYaml(scenario_file);
  for (const auto& assignment : overrides) {
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw std::invalid_argument("--set '" + assignment + "': expected key.path=value");
    }
    const std::string path = assignment.substr(0, eq);
    std::vector<std::string> keys;
    for (std::size_t start = 0;;) {
      const auto dot = path.find('.', start);
      keys.push_back(path.substr(start, dot - start));
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
    // yaml-cpp nodes are handles: walking with operator[] on copies keeps
    // writing into the same tree.
    std::vector<YAML::Node> chain{root};
    for (std::size_t i = 0; i + 1 < keys.size(); ++i) chain.push_back(chain.back()[keys[i]]);
    chain.back()[keys.back()] = YAML::Load(assignment.substr(eq + 1));
  }
  fs::create_directories(run_dir);
  const std::string out = (fs::path(run_dir) / "scenario.yaml").string();
  // Written aside and renamed: a process on another host or container that
  // waits for this file never reads half of it.
  const std::string partial = out + ".partial";
  {
    std::ofstream file(partial);
    file << "# Resolved from " << fs::absolute(scenario_file).string() << "\n" << root << "\n";
    if (!file.flush()) throw std::runtime_error(partial + ": cannot write");
  }
  fs::rename(partial, out);
  return out;
}


std::string attributeProblem(const std::string& problem, const std::string& resolved,
                             const std::string& scenario_file, const std::vector<std::string>& overrides) {
  // "<resolved>:L:C: key: reason" or "<resolved>: key: reason"
  if (problem.rfind(resolved + ":", 0) != 0) return problem;
  const auto place_end = problem.find(": ", resolved.size());
  if (place_end == std::string::npos) return problem;
  const auto key_end = problem.find(": ", place_end + 2);
  const std::string key = problem.substr(place_end + 2, key_end == std::string::npos ? std::string::npos
                                                                                     : key_end - place_end - 2);
  for (const auto& assignment : overrides) {
    const std::string set_key = assignment.substr(0, assignment.find('='));
    if (key == set_key || key.rfind(set_key + ".", 0) == 0 || key.rfind(set_key + "[", 0) == 0) {
      return "--set " + assignment + ": " + problem.substr(place_end + 2);
    }
  }
  // Placed in the user's file, or in the base that writes the key.
  std::vector<std::string> files;
  try {
    bus::loadScenarioYaml(scenario_file, &files);
  } catch (const bus::ScenarioError&) {
    files = {scenario_file};
  }
  return bus::placeProblem(scenario_file + ": " + problem.substr(place_end + 2), scenario_file, files);
}

std::string recordOnceASecond(double step_s) {
  return "components.recorder.record_every_steps=" + std::to_string(std::max(1L, std::lround(1.0 / step_s)));
}

std::string defaultRunDirectory(const std::string& scenario_name) {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", std::gmtime(&now));
  return (fs::path("runs") / (scenario_name + "-" + stamp)).string();
}

}  // namespace flatsat::rig
