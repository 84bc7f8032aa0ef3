// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/common/WheelGeometry.hpp"
#include "sim/Thrusters.hpp"

namespace flatsat::thruster_sequencer {

struct GimbalDumpingParams {
  std::vector<sim::ThrusterParams> thrusters;  ///< the plant's, gimbals included
  WheelGeometry wheels;                        ///< the wheels whose momentum is dumped
  /// [s] the longest a dump burn takes to answer the momentum, [60, 864000]
  double dump_time_s = 43200.0;

  std::vector<std::string> validate() const;
};

/// Seed S3's momentum dumping by gimbal offsets (JP3299143, Table I "MD"): a
/// thrust line through the centre of mass gives no torque; turned by small
/// gimbal angles θ it gives τ = F r × (θ₁ a₁ × d₀ + θ₂ a₂ × d₀) to first order
/// (d = R(a₁, θ₁) R(a₂, θ₂) d₀, Thrusters.hpp). The firings the table gives to
/// MD share the torque −H_w / T, H_w the wheels' stored momentum, T what is
/// left of the longest dump burn under way (at least a step, at most
/// dump_time_s): each burn dumps what its gimbals reach before it ends,
/// which between the two of a Table I pair (whose torque planes differ,
/// StationKeepingPlanner.hpp) leaves no direction undumped. The angles are the
/// least-squares ones (the smallest where several do), each clamped to its
/// gimbal's limits. Thrusters not fitted with gimbals, or not dumping, keep
/// their angles at zero.
class GimbalDumping {
 public:
  /// @throws std::invalid_argument naming every problem of params.validate().
  explicit GimbalDumping(const GimbalDumpingParams& params);
  /// [rad] Gimbal angles for a step of step_s [s] in which thruster i is on
  /// for on_time_s(i) and dumps where dump_left_s(i) [s], the time left on its
  /// dump burn from the step's start, is positive, with the wheels at
  /// wheel_speed_rad_s [rad/s] (relative to the body).
  sim::ThrusterGimbals angles(const sim::ThrusterVector& on_time_s, const sim::ThrusterVector& dump_left_s,
                              const Eigen::Vector4d& wheel_speed_rad_s, double step_s) const;

 private:
  GimbalDumpingParams params_;
};

}  // namespace flatsat::thruster_sequencer
