// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat plot RECORDING`: the PNG figures a reviewer expects (pointing
/// error, body rates, wheels, dipole, field, estimator error with 3σ,
/// thruster firings, ground track),
/// drawn by gnuplot from data files and a script written next to them.
/// Sets exit_code when it runs: 0; 1 when it cannot read, write or plot.
CLI::App* addPlotCommand(CLI::App& app, int& exit_code);

/// The figures of a run's recording into `out_dir` (scenario.yaml next to the
/// recording gives the limits); `list`: print each PNG's path on stdout.
/// 0 when every figure was written, else 1 with the reason on stderr.
int plotRecording(const std::string& recording, const std::string& out_dir, bool list);

}  // namespace flatsat::tools
