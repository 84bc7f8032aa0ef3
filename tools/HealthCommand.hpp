// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat health`: a table of the rig's components (state, steps done,
/// message, age of the last health) refreshed every second; `--once`
/// prints one table. Sets exit_code when it runs: 0; 1 when no component
/// reported (--once).
CLI::App* addHealthCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
