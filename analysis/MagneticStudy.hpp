// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <optional>

#include "analysis/MagneticMetrics.hpp"
#include "bus/Scenario.hpp"

namespace flatsat::analysis {

/// One seeded case of a magnetic study.
struct MagneticCase {
  MagneticMetricsResult metrics;
  std::optional<double> handover_s;    ///< [s] when detumble handed over, if it did
  double orbit_period_s = 0.0;         ///< [s]
  double fifth_orbit_axis_deg = 0.0;   ///< [deg] worst spin-axis error over orbit 5 (4 to 5 periods)
  double fifth_orbit_rate_pct = 0.0;   ///< [%] worst spin-rate error over orbit 5
};

/// The scenario's plant (DynamicsModel), magnetometer model and magnetic
/// controller (MagneticModes) in one process, no DDS, with the scenario's seed
/// replaced by `seed` (the seeds of `flatsat run --seed`): at step k the
/// magnetometer samples truth(k), the controller answers from that sample, and
/// the dipole is held over [k, k+1), as the lockstep rig does.
/// @throws std::invalid_argument listing the scenario's problems.
MagneticCase runMagneticCase(bus::Scenario scenario, std::uint64_t seed);

}  // namespace flatsat::analysis
