// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat hz TOPIC`: the rate of one topic in wall time: mean rate and the
/// interval's min, max and standard deviation. Sets exit_code when it runs:
/// 0; 1 when fewer than two samples came; 2 for an unknown topic.
CLI::App* addHzCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
