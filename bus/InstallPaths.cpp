// SPDX-License-Identifier: Apache-2.0
#include "bus/InstallPaths.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>

namespace flatsat::bus {
namespace fs = std::filesystem;

namespace {

std::vector<fs::path> fromEnvironment(const char* variable) {
  std::vector<fs::path> dirs;
  const char* value = std::getenv(variable);
  if (value == nullptr) return dirs;
  std::stringstream list(value);
  std::string dir;
  while (std::getline(list, dir, ':')) {
    if (!dir.empty()) dirs.emplace_back(dir);
  }
  return dirs;
}

std::vector<fs::path> searchPath(const char* variable, const char* share_subdir) {
  auto dirs = fromEnvironment(variable);
  dirs.push_back(installShareDir() / share_subdir);
  return dirs;
}

}  // namespace

fs::path installShareDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return fs::path("/usr/share/flatsat");
  return exe.parent_path().parent_path() / "share" / "flatsat";
}

std::vector<fs::path> dataDirs() { return searchPath("FLATSAT_DATA_DIR", "data"); }
std::vector<fs::path> scenarioDirs() { return searchPath("FLATSAT_SCENARIO_PATH", "scenarios"); }
std::vector<fs::path> deviceDirs() { return searchPath("FLATSAT_DEVICES_DIR", "devices"); }

std::optional<fs::path> findIn(const std::vector<fs::path>& dirs, const fs::path& relative) {
  for (const auto& dir : dirs) {
    std::error_code ec;
    if (fs::is_regular_file(dir / relative, ec)) return dir / relative;
  }
  return std::nullopt;
}

std::string findBesideOrIn(const std::string& scenario_file, const std::string& name,
                           const std::vector<fs::path>& dirs) {
  const fs::path given(name);
  if (given.is_absolute()) return name;
  const fs::path beside = fs::path(scenario_file).parent_path() / given;
  std::error_code ec;
  if (fs::exists(beside, ec)) return beside.string();
  if (const auto found = findIn(dirs, given)) return found->string();
  return name;
}

std::optional<std::string> resolveScenario(const std::string& given) {
  std::error_code ec;
  if (fs::is_regular_file(given, ec)) return given;
  // Only a bare name is looked up: a path that does not exist is the user's typo.
  if (given.empty() || given.find('/') != std::string::npos) return std::nullopt;
  if (const auto found = findIn(scenarioDirs(), given)) return found->string();
  if (fs::path(given).extension() != ".yaml") {
    if (const auto found = findIn(scenarioDirs(), given + ".yaml")) return found->string();
  }
  return std::nullopt;
}

std::string scenarioNotFound(const std::string& given) {
  if (given.find('/') != std::string::npos) return given + ": no such file";
  return given + ": no such file here, and no scenario of that name in " + listOfDirs(scenarioDirs()) +
         " (FLATSAT_SCENARIO_PATH adds folders; `flatsat scenarios` lists them)";
}

std::string installedScenario(const std::string& name) {
  if (const auto found = findIn(scenarioDirs(), name)) return found->string();
  return name;
}

std::vector<fs::path> scenarioFilesIn(const fs::path& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return files;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string listOfDirs(const std::vector<fs::path>& dirs) {
  std::string text;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    if (i > 0) text += i + 1 == dirs.size() ? " or " : ", ";
    text += dirs[i].string();
  }
  return text;
}

}  // namespace flatsat::bus
