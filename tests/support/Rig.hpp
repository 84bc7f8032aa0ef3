// SPDX-License-Identifier: Apache-2.0
#pragma once
// Whole-rig runs for the system tests: `flatsat run SCENARIO` on the test's own
// domain, judged on its summary.json. Needs FLATSAT_BIN_DIR and Catch2.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tests/support/Run.hpp"
#include "tests/support/TestDomain.hpp"

namespace flatsat::test {

inline const std::string kFlatsat = std::string(FLATSAT_BIN_DIR) + "/flatsat";

/// An empty temporary directory path unique to this test process and tag.
inline std::string freshDir(const std::string& tag) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("flatsat-test-" + tag + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir.string();
}

struct RigRun {
  CommandResult command;
  nlohmann::json summary;
};

/// Runs the scenario to its end into `out` with extra flags; requires success,
/// reads the summary and removes the run directory (kept when the run failed).
inline RigRun runScenario(const std::string& scenario, const std::string& out,
                          const std::string& extra = "") {
  exportTestDomain();
  RigRun run;
  run.command = runCommand(kFlatsat + " run " + scenario + " -q --no-plots --out " + out + " " + extra);
  INFO(run.command.output);
  REQUIRE(run.command.exit_code == 0);
  std::ifstream(std::filesystem::path(out) / "summary.json") >> run.summary;
  std::filesystem::remove_all(out);
  return run;
}

}  // namespace flatsat::test
