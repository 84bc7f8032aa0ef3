// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sim/Thrusters.hpp"

namespace flatsat::thruster_sequencer {

struct StationKeepingFiringsParams {
  double step_s = 60.0;               ///< [s] the sequencer's step, (0, 3600]
  double ra_rate_rad_s = 7.2921e-5;   ///< [rad/s] the spacecraft's mean rate of right ascension, (0, 0.01]
  int thruster_count = 6;             ///< [-] thrusters of the plant, 1..sim::kMaxThrusters

  std::vector<std::string> validate() const;
};

/// One firing of a station-keeping plan: `thruster` (index into the plant's
/// thrusters) for `duration_s` centred on right ascension `ra_rad`.
struct ScheduledFiring {
  int thruster = 0;
  double ra_rad = 0.0;      ///< [rad]
  double duration_s = 0.0;  ///< [s] ≥ 0
  bool dumps = false;       ///< Table I gives it momentum dumping (MD): its gimbal may turn
};

/// What the firings ask of the thrusters over one step.
struct StationKeepingFiringsOutput {
  sim::ThrusterVector on_time_s = sim::ThrusterVector::Zero();  ///< [s]
  /// [s] what is left of a dump firing burning on it, from the step's start; 0: none
  sim::ThrusterVector dump_left_s = sim::ThrusterVector::Zero();
};

/// Flies seed S3's plans as finite burns: each firing starts when the
/// spacecraft's right ascension reaches the start of its arc (half the burn
/// ahead of its centre, so the burn is centred where the plan put the
/// impulse) and runs at full thrust until its duration is spent, step by
/// step. A new plan replaces the firings not yet begun; a burn under way runs
/// to its end. A firing whose arc the spacecraft is already in when the plan
/// comes starts at once if the centre is still ahead.
class StationKeepingFirings {
 public:
  /// @throws std::invalid_argument naming every problem of params.validate().
  explicit StationKeepingFirings(const StationKeepingFiringsParams& params);
  void reset();
  /// The plan made at step `plan_step`: taken once (the same plan again is ignored).
  void plan(std::uint64_t plan_step, const std::vector<ScheduledFiring>& firings);
  /// The thrusters' on-times over the step starting at right ascension ra_rad.
  StationKeepingFiringsOutput step(double ra_rad);

 private:
  struct Pending {
    ScheduledFiring firing;
    double remaining_s = 0.0;
    bool burning = false;
  };
  StationKeepingFiringsParams params_;
  std::vector<Pending> pending_;
  std::uint64_t plan_step_ = 0;
  bool has_plan_ = false;
};

}  // namespace flatsat::thruster_sequencer
