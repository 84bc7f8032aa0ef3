// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// `flatsat plot RECORDING`: the PNG figures a reviewer expects (pointing
/// error, body rates, wheels, dipole, field, estimator error, ground track),
/// drawn by gnuplot from data files and a script written next to them.
/// Sets exit_code when it runs: 0; 1 when it cannot read, write or plot.
CLI::App* addPlotCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
