// SPDX-License-Identifier: Apache-2.0
#pragma once
// flatsat scenarios: the scenarios `flatsat run NAME` finds, with their
// descriptions, folder by folder of the scenario search path.
#include <CLI/CLI.hpp>

namespace flatsat::tools {

CLI::App* addScenariosCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
