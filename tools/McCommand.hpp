// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// Registers `flatsat mc SCENARIO --runs N [--jobs J] [--out DIR] [--seed0 S]
/// [--set key=value ...]`: a Monte Carlo campaign. Run i is
/// `flatsat run SCENARIO --composed --seed S+i --no-plots -q --out DIR/run-<i>`
/// with the --set overrides, in its own process, J at a time; the seed draws
/// the sensors' noise and the initial tumble where the scenario asks for one
/// (initial.tumble_rate_rad_s). S defaults to the scenario's seed, DIR to
/// runs/<name>-mc-<time>. Writes DIR/mc.csv (one row per run) and
/// DIR/mc_summary.json (statistics of every numeric summary key over the
/// successful runs, and the failed runs with their exit codes and logs,
/// DIR/run-<i>.log), prints the table and shows progress on stderr.
/// Exit status: 0 every run succeeded, 1 some failed, 2 bad input.
CLI::App* addMcCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
