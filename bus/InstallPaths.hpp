// SPDX-License-Identifier: Apache-2.0
#pragma once
// Where the installed data, scenarios and device descriptions are, found from
// the running executable's own place (PREFIX/bin/EXE -> PREFIX/share/flatsat),
// so an install moved to another prefix, a .deb under /usr and the build tree
// (whose share/flatsat links to the sources, made at configure time) all work
// with nothing of the build machine compiled in. Environment variables put
// folders of the user's own first.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace flatsat::bus {

/// PREFIX/share/flatsat of the running executable.
std::filesystem::path installShareDir();

/// FLATSAT_DATA_DIR (a ':' list), then PREFIX/share/flatsat/data.
std::vector<std::filesystem::path> dataDirs();
/// FLATSAT_SCENARIO_PATH (a ':' list), then PREFIX/share/flatsat/scenarios.
std::vector<std::filesystem::path> scenarioDirs();
/// FLATSAT_DEVICES_DIR (a ':' list), then PREFIX/share/flatsat/devices.
std::vector<std::filesystem::path> deviceDirs();

/// The first dirs[i]/relative that exists.
std::optional<std::filesystem::path> findIn(const std::vector<std::filesystem::path>& dirs,
                                            const std::filesystem::path& relative);

/// A file named in a scenario (a data table, a device description): as given
/// when absolute; else beside the scenario; else in dirs; else as given (its
/// reader then reports it missing by that name).
std::string findBesideOrIn(const std::string& scenario_file, const std::string& name,
                           const std::vector<std::filesystem::path>& dirs);

/// A scenario as the user names it: a file that exists (a path), or a bare
/// name such as `default` or `default.yaml` looked up in scenarioDirs().
/// nullopt when neither; scenarioNotFound() then says where it looked.
std::optional<std::string> resolveScenario(const std::string& given);
std::string scenarioNotFound(const std::string& given);

/// The installed scenario `name` (e.g. "default.yaml"), or the name itself
/// when none is installed (the caller's error then names it).
std::string installedScenario(const std::string& name);

/// The scenario files (*.yaml) in `dir`, sorted by name; none when it is no folder.
std::vector<std::filesystem::path> scenarioFilesIn(const std::filesystem::path& dir);

/// "a, b or c" of the folders, for an error that says where it looked.
std::string listOfDirs(const std::vector<std::filesystem::path>& dirs);

}  // namespace flatsat::bus
