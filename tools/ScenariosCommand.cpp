// SPDX-License-Identifier: Apache-2.0
#include "tools/ScenariosCommand.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <set>

#include <yaml-cpp/yaml.h>

#include "bus/InstallPaths.hpp"

namespace flatsat::tools {
namespace {

namespace fs = std::filesystem;

/// A scenario's `description`, read without resolving its base (a listing
/// should not fail on one broken file); empty when it has none.
std::string descriptionOf(const fs::path& file) {
  try {
    const YAML::Node root = YAML::LoadFile(file.string());
    if (root["description"] && root["description"].IsScalar()) return root["description"].as<std::string>();
  } catch (const YAML::Exception& e) {
    return std::string("(unreadable: ") + e.what() + ")";
  }
  return {};
}

int listScenarios() {
  std::set<std::string> seen;  // an earlier folder's scenario hides a later one of the same name
  for (const auto& dir : bus::scenarioDirs()) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    const auto files = bus::scenarioFilesIn(dir);
    std::cout << dir.string() << ":\n";
    for (const auto& file : files) {
      const std::string name = file.stem().string();
      const bool hidden = !seen.insert(name).second;
      std::printf("  %-28s %s%s\n", name.c_str(), descriptionOf(file).c_str(), hidden ? " (hidden by the one above)" : "");
    }
  }
  if (seen.empty()) {
    std::cerr << "error: no scenarios in " << bus::listOfDirs(bus::scenarioDirs()) << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

CLI::App* addScenariosCommand(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("scenarios",
                                 "list the scenarios `flatsat run NAME` finds: FLATSAT_SCENARIO_PATH, "
                                 "then the installed ones");
  cmd->callback([&exit_code] { exit_code = listScenarios(); });
  return cmd;
}

}  // namespace flatsat::tools
