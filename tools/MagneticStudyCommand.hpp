// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// Registers `flatsat study detumble|spin [--cases N] [--scenario FILE]` under `study`:
/// analysis::runMagneticCase once per seed 1..N, printing one row per case (time to
/// detumble or capture, final rate, spin-axis and rate errors, coil duty) and a pass
/// count against the limits (detumble: < 0.2 deg/s within 3 orbits; spin: within
/// 5 deg and 5 % within 5 orbits, held to the end of the run). The defaults are
/// deploy/scenarios/detumble.yaml and s4_spin.yaml. exit_code: 0, 2 for bad input.
void addMagneticStudies(CLI::App& study, int& exit_code);

}  // namespace flatsat::tools
