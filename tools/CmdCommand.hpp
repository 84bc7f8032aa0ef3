// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat cmd mode|fault|param ...`: sends one command to a running rig
/// and waits for the component's acknowledgement (flatsat/command_ack).
/// Sets exit_code: 0 accepted, 3 refused, 1 no acknowledgement in time,
/// 2 bad input.
CLI::App* addCmdCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
