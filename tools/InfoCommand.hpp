// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat info RECORDING [--json]`: what a recording holds, as `ros2 bag info` tells
/// of a bag (analysis/RecordingInfo). Sets exit_code when it runs: 0, or 1 when the
/// recording cannot be read.
CLI::App* addInfoCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
