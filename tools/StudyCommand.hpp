// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <CLI/CLI.hpp>

namespace flatsat::tools {

/// Registers `flatsat study s1 [SCENARIO] [--cases N] [--seed N] [--max-angle-deg A]
/// [--max-rate-deg-s W] [--disturbance-Nm D] [--duration-s T] [--set key=value ...]`:
/// seed S1's convergence study at the algorithm level (no bus). The scenario (default
/// s1_example.yaml, with the --set overrides) gives the sequencer, the thrusters, the
/// inertia and the Sun sensor's field of view; N seeded cases of initial angle in ±A and
/// rate in ±W about the controlled axis run without and with a constant disturbance D
/// (thruster_sequencer::runAngleOnlyCase). Prints per set the cases that settled, their
/// pulse counts (to settle, and over the whole run with the limit cycle's upkeep) and settle
/// times (min, median, 90th percentile, max) and the largest excursion. Exit status: 0 every case settled, 1 some did not, 2 bad input.
CLI::App* addStudyCommand(CLI::App& app, int& exit_code);

}  // namespace flatsat::tools
