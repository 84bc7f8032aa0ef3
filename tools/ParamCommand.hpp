// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat param list [COMPONENT]`, `param get COMPONENT KEY`, `param set
/// COMPONENT KEY VALUE`, as `ros2 param`: the parameters components let an
/// operator set while they run, read from their flatsat/param_state
/// announcements; set is `flatsat cmd param`.
CLI::App* addParamCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
