// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat cmd mode|fault|param ...`: sends one command to a running rig
/// and waits for the component's acknowledgement (flatsat/command_ack).
/// Sets exit_code: 0 accepted, 3 refused, 1 no acknowledgement in time,
/// 2 bad input.
CLI::App* addCmdCommand(CLI::App& app, int& exit_code);

/// `flatsat cmd param TARGET KEY VALUE` (also `flatsat param set`): the same
/// exit codes.
int sendParamCommand(const std::string& target, const std::string& key, double value, double timeout_s, int domain);

}  // namespace flatsat::tools
