// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat record -o FILE`: attaches to a running rig and records chosen
/// or all topics into a recording of the rig's own format (SQLite, CDR
/// bytes by topic, step and source) until the rig's stop grant, a time
/// limit or Ctrl-C. Sets exit_code: 0 recorded, 1 nothing came, 2 bad input.
CLI::App* addRecordCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
