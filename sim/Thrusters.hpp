// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace flatsat::sim {

/// Command and report slots per spacecraft (S3 uses six, a full RCS twelve).
inline constexpr int kMaxThrusters = 12;

using ThrusterVector = Eigen::Matrix<double, kMaxThrusters, 1>;
using ThrusterGimbals = Eigen::Matrix<double, 2, kMaxThrusters>;  // column i: (angle 1, angle 2) of thruster i

/// One thruster. The gimbal, when fitted, turns the thrust direction by angle 1
/// about axis 1 (fixed in the body, outer ring) after angle 2 about axis 2 (the
/// inner ring, given at zero angles): d = R(a1, θ1) R(a2, θ2) d0, right-handed.
struct ThrusterParams {
  Eigen::Vector3d r_B_m = Eigen::Vector3d::Zero();          // [m] thrust point (gimbal pivot) from the centre of mass
  Eigen::Vector3d direction_B = Eigen::Vector3d::UnitX();   // [-] unit, force on the spacecraft at zero gimbal angles
  double thrust_N = 0.0;                                    // [N] steady thrust, > 0
  double min_impulse_bit_Ns = 0.0;                          // [N s] smallest impulse, ≥ 0; 0: continuous on-time
  bool gimballed = false;                                   // the two gimbal angles below apply
  Eigen::Vector3d gimbal_axis1_B = Eigen::Vector3d::UnitY();  // [-] unit, outer axis
  Eigen::Vector3d gimbal_axis2_B = Eigen::Vector3d::UnitZ();  // [-] unit, inner axis at zero angles
  Eigen::Vector2d gimbal_min_rad = Eigen::Vector2d::Zero();   // [rad] lower limits (angle 1, angle 2), ≥ −π
  Eigen::Vector2d gimbal_max_rad = Eigen::Vector2d::Zero();   // [rad] upper limits, ≥ min, ≤ π
  bool failed = false;                                      // delivers nothing whatever the command

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// What a thruster set delivered over one step.
struct ThrusterOutput {
  Eigen::Vector3d force_B_N = Eigen::Vector3d::Zero();     // [N] mean force over the step
  Eigen::Vector3d torque_B_Nm = Eigen::Vector3d::Zero();   // [N m] mean torque about the centre of mass
  ThrusterVector on_time_s = ThrusterVector::Zero();       // [s] delivered on-time per thruster
  ThrusterVector impulse_Ns = ThrusterVector::Zero();      // [N s] delivered impulse per thruster
  ThrusterGimbals gimbal_rad = ThrusterGimbals::Zero();    // [rad] angles after the limits
};

/// On/off thrusters with pulse-width commands. Model: a rectangular thrust
/// pulse (rise and tail-off neglected) of the commanded on-time, cut to the
/// step; the valve driver resolves on-time in whole minimum pulses
/// t_min = I_bit / F, so the delivered on-time is t_min ⌊t_on / t_min⌋ and the
/// impulse F t_min ⌊·⌋ is quantised by the minimum impulse bit — a pulse shorter
/// than t_min gives none (the minimum impulse bit of on/off thrusters; Wie, Space
/// Vehicle Dynamics and Control, ch. 7, thruster pulse modulation). A failed
/// thruster delivers nothing. The step's impulse is reported as a mean force and
/// torque over the step, so the angular impulse is exact and only its timing
/// within the step is smeared.
class Thrusters {
 public:
  /// Every thruster must be valid; at most kMaxThrusters (extra ones ignored).
  explicit Thrusters(std::vector<ThrusterParams> thrusters);

  int count() const { return count_; }

  /// [-] Thrust direction of thruster i at the given gimbal angles (ignored when not gimballed).
  Eigen::Vector3d direction_B(int i, const Eigen::Vector2d& gimbal_rad) const;

  /// Fires on_time_s(i) [s] (clamped to [0, dt_s]; non-finite → 0) with the gimbal
  /// angles [rad] (clamped to the limits; non-finite → 0) over a step of dt_s > 0.
  ThrusterOutput fire(const ThrusterVector& on_time_s, const ThrusterGimbals& gimbal_rad, double dt_s) const;

 private:
  std::vector<ThrusterParams> thrusters_;
  int count_;
};

}  // namespace flatsat::sim
