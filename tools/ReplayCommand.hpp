// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat replay RECORDING`: publishes a recording's stepped topics back
/// onto the bus, acting as the time master, so that one component can be
/// re-run against recorded inputs; optionally captures what that component
/// publishes and compares it with the recording. Sets exit_code: 0 done,
/// 1 failed (a component failed or stalled), 2 bad input.
CLI::App* addReplayCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
