// SPDX-License-Identifier: Apache-2.0
#pragma once
// A scenario argument as the user writes it: a file, or the name of one in the
// scenario search path (`flatsat run default`). Resolved when the command line
// is parsed, so a name that matches nothing is a usage error (exit 2) that says
// where it looked.
#include <CLI/CLI.hpp>

#include "bus/InstallPaths.hpp"

namespace flatsat::tools {

inline CLI::Validator scenarioByName() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        const auto resolved = bus::resolveScenario(value);
        if (!resolved) return bus::scenarioNotFound(value);
        value = *resolved;
        return {};
      },
      "SCENARIO", "scenario file or name");
}

}  // namespace flatsat::tools
