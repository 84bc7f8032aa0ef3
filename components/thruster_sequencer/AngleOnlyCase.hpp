// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <vector>

#include "components/thruster_sequencer/AngleOnlySequencer.hpp"

namespace flatsat::thruster_sequencer {

/// One closed-loop case of the S1 sequencer without the bus: the body turns about the
/// controlled axis only, driven by the sequencer's thrusters (sim::Thrusters, minimum
/// impulse bit included) and a constant disturbance torque; the Sun sensor is noiseless and
/// sees the Sun within its field of view only.
struct AngleOnlyCaseSetup {
  double angle0_rad = 0.0;               // [rad] initial angle about the axis
  double rate0_rad_s = 0.0;              // [rad/s] initial rate about the axis
  double disturbance_Nm = 0.0;           // [N m] constant torque about the axis
  double duration_s = 3000.0;            // [s] simulated time, > 0
  double fov_half_angle_rad = 1.0471975511965976;  // [rad] Sun sensor field of view (60°)
};

struct AngleOnlyCaseResult {
  PulseTally pulses;                  // [-] counts per correction and braking
  double final_angle_rad = 0.0;       // [rad]
  double final_rate_rad_s = 0.0;      // [rad/s]
  double max_angle_rad = 0.0;         // [rad] largest |angle − A1| reached
  double settle_time_s = 0.0;         // [s] from here on inside the limit range (± margin)
  int pulses_to_settle = 0;           // [-] pulses fired before settle_time_s
  bool settled = false;               // inside (± margin) for the last quarter of the run
};

/// Runs one case at the sequencer's step; the commands of step k act over [t_k, t_k+1) as on
/// the rig. Between steps the axis is a double integrator under the step's mean torque.
/// "Inside" allows a margin of |δω| times one step plus the steps a pulse is spread over:
/// the limits are sampled and a pulse acts over its on-time, so a residual drift below δω
/// crosses a limit by up to that much before the correction pulse has turned it back.
AngleOnlyCaseResult runAngleOnlyCase(const AngleOnlySequencerParams& params, const AngleOnlyCaseSetup& setup);

/// `count` cases with initial angle uniform in ±max_angle_rad and rate in ±max_rate_rad_s
/// (std::mt19937_64 from `seed`), each with the given disturbance and duration.
std::vector<AngleOnlyCaseSetup> seededCases(std::uint64_t seed, int count, double max_angle_rad,
                                            double max_rate_rad_s, double disturbance_Nm, double duration_s);

}  // namespace flatsat::thruster_sequencer
