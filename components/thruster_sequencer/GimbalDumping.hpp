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
  double dump_time_s = 3600.0;                 ///< [s] the firings' torque aims at −H / dump_time_s, [60, 864000]

  std::vector<std::string> validate() const;
};

/// Seed S3's momentum dumping by gimbal offsets (JP3299143, Table I "MD"): a
/// thrust line through the centre of mass gives no torque; turned by small
/// gimbal angles θ it gives τ = F r × (θ₁ a₁ × d₀ + θ₂ a₂ × d₀) to first order
/// (d = R(a₁, θ₁) R(a₂, θ₂) d₀, Thrusters.hpp). The firings the table gives to
/// MD share the torque −H_w / dump_time_s, H_w the wheels' stored momentum:
/// the least-squares angles (the smallest where several do), each clamped to
/// its gimbal's limits. Thrusters not fitted with gimbals, or not dumping, keep
/// their angles at zero.
class GimbalDumping {
 public:
  /// @throws std::invalid_argument naming every problem of params.validate().
  explicit GimbalDumping(const GimbalDumpingParams& params);
  /// [rad] Gimbal angles for a step of step_s [s] in which thruster i is on
  /// for on_time_s(i) and dumps where `dumping(i)` is non-zero, with the
  /// wheels at wheel_speed_rad_s [rad/s] (relative to the body).
  sim::ThrusterGimbals angles(const sim::ThrusterVector& on_time_s, const sim::ThrusterVector& dumping,
                              const Eigen::Vector4d& wheel_speed_rad_s, double step_s) const;

 private:
  GimbalDumpingParams params_;
};

}  // namespace flatsat::thruster_sequencer
