// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat topics`: every live topic (a writer announced it or sent a sample;
/// --all: the whole registry) with its type, its producers and the rate
/// measured over a few seconds.
/// Sets exit_code when it runs: 0, or 1 when nothing is on the domain.
CLI::App* addTopicsCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
