// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// Registers `flatsat soak [SCENARIO] [--minutes M] [--kill-every-s MIN MAX] [--seed N]
/// [--out DIR] [--set key=value ...]`: the scenario paced with `flatsat run --restart` for
/// M minutes while a seeded random non-server component (never the dynamics server or the
/// recorder, the instrument) is SIGKILLed every MIN..MAX seconds, until 15 s before the
/// end. Then it checks the run: it completed; every kill is one restart in summary.json and
/// one `restarted` FaultEvent in the recording; no (topic, source, step) is recorded twice;
/// truth holds every step; each producer never killed has as many samples of each of its
/// topics as steps its log says it did (nothing lost after a commit); the resident memory
/// of each process not restarted grew by at most max(10 %, 4 MiB) from 10 s after the start
/// to 10 s before the end. Prints a table, writes DIR/soak.json. Exit status: 0 every check
/// held, 1 one failed, 2 bad input.
CLI::App* addSoakCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
