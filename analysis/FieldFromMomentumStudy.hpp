// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <string>

namespace flatsat::analysis {

struct FieldFromMomentumStudyOptions {
  std::string scenario;   // the plant, sensors and attitude loop to study
  double orbits = 1.0;    // [-] simulated span of each case
  double cycle_s = 300.0; // [s] from one S0 window to the next
  // One case instead of the grid when all three are set:
  std::string form;         // seed | settle | settle+q | total+q
  double window_s = 0.0;    // [s] Δt1 = pulse
  double dipole_Am2 = 0.0;  // [A m²]
};

/// Seed S0's accuracy over a grid of window lengths (Δt1 = pulse), settle times
/// and dipoles, in-process (the scenario's plant, tachometers, gyro and attitude
/// loop, no bus); prints one table row per case. Returns the exit code.
int runFieldFromMomentumStudy(const FieldFromMomentumStudyOptions& options);

}  // namespace flatsat::analysis
