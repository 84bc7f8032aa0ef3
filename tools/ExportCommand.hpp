// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat export RECORDING --csv|--json`: one CSV (a header row of field
/// names with units) or JSON-lines file per recorded topic. Sets exit_code
/// when it runs: 0; 1 when it cannot read or write; 2 for bad arguments.
CLI::App* addExportCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
