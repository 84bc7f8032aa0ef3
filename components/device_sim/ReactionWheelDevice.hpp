// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <deque>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace flatsat::device_sim {

struct ReactionWheelDeviceParams {
  int wheel_count = 4;                   // [-] wheels the unit drives, 1..4
  Eigen::Vector4d inertia_kg_m2 = Eigen::Vector4d::Constant(0.12);  // [kg m^2] rotor axial inertia, > 0 for each driven wheel
  double max_torque_Nm = 0.2;            // [N m] the drive's torque limit, (0, 10]
  double response_delay_s = 0.02;        // [s] from a command's arrival to its torque, [0, 10]

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// A reaction wheel unit as it behaves on the bench (the device end of
/// deploy/devices/reaction_wheel.yaml): a torque command acts response_delay_s after it
/// arrives, held to max_torque_Nm per wheel, until the next one acts; each rotor's speed
/// integrates the torque in force, I_w dΩ/dt = τ, exactly across the switching instants.
/// No bearing friction: the plant, whose rotors follow these speeds, carries its own.
class ReactionWheelDevice {
 public:
  using Params = ReactionWheelDeviceParams;

  explicit ReactionWheelDevice(const Params& params);

  /// Rotor speeds at t_s; no torque until a command acts.
  void reset(const Eigen::Vector4d& speed_rad_s, double t_s);
  /// A command of motor torques that arrived at t_s (at or after the last time given);
  /// false, and ignored, when a torque is not finite.
  bool command(const Eigen::Vector4d& torque_Nm, double t_s);
  /// Rotor speeds [rad/s] at t_s, the torques in force integrated since the last time
  /// (a t_s before it changes nothing: the unit's clock does not run back).
  const Eigen::Vector4d& step(double t_s);
  /// The motor torques in force now [N m], after the limit.
  const Eigen::Vector4d& appliedTorque() const { return applied_; }

 private:
  Params params_;
  std::deque<std::pair<double, Eigen::Vector4d>> pending_;  // (time it acts, limited torque)
  Eigen::Vector4d speed_ = Eigen::Vector4d::Zero();
  Eigen::Vector4d applied_ = Eigen::Vector4d::Zero();
  double t_ = 0.0;
};

}  // namespace flatsat::device_sim
