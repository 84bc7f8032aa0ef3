// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat echo TOPIC`: prints the samples of one topic as they arrive, one
/// line each, or pretty JSON. Sets exit_code when it runs: 0; 1 when
/// --timeout passed before --count samples; 2 for an unknown topic.
CLI::App* addEchoCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
