// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// Registers `flatsat mc`, a Monte Carlo campaign, and the hidden `mc-task`
/// its Slurm array tasks run:
///   flatsat mc SCENARIO --runs N [--jobs J] [--out DIR] [--seed0 S] [--set k=v ...]
///   flatsat mc SCENARIO --runs N --slurm [--per-task K] [--partition P] [--time T] [--no-wait] ...
///   flatsat mc --collect DIR          gather (following the Slurm job while it runs)
///   flatsat mc --resume DIR [--slurm] run again only the runs that did not succeed
/// Run i is `flatsat run DIR/scenario.yaml --composed --seed S+i --no-plots -q
/// --out DIR/run-<i>`, the same command here and on a cluster's node, so a
/// run's recording is the same wherever it ran (rig/Campaign.hpp has the
/// directory's layout). The seed draws the sensors' noise and the initial
/// tumble where the scenario asks for one. S defaults to the scenario's seed,
/// DIR to runs/<name>-mc-<time>. Writes DIR/mc.csv (one row per run) and
/// DIR/mc_summary.json (statistics of every numeric summary key over the
/// successful runs; the failed runs with their exit codes, reasons and logs;
/// the campaign's CPU against its runs'), prints the table and shows progress
/// on stderr. Exit status: 0 every run succeeded, 1 some failed, 2 bad input,
/// 130 interrupted.
CLI::App* addMcCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
