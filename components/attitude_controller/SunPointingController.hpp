// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "components/common/WheelGeometry.hpp"

namespace flatsat::attitude_controller {

/// PD gains, rate and torque limits and wheel geometry of the Sun-pointing loop.
struct SunPointingControllerParams {
  double kp_Nm_per_rad = 0.02;    // [Nm/rad] attitude gain, > 0
  double kd_Nm_s_per_rad = 0.2;   // [Nm·s/rad] rate gain, > 0
  double max_torque_Nm = 0.01;    // [Nm] limit of |τ_cmd|, > 0
  double max_rate_rad_s = 0.005;  // [rad/s] limit of the slew rate k_p/k_d·|e|, > 0
  Eigen::Vector3d pointing_axis_B = Eigen::Vector3d::UnitX();  // [-] body axis put on the Sun, unit
  WheelGeometry wheels;           // [-] live wheels, spin axes, rotor inertias (see WheelGeometry)

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct SunPointingControllerInput {
  Eigen::Vector3d sun_B_est_unit = Eigen::Vector3d::Zero();     // [-] estimated Sun direction, body
  Eigen::Vector3d w_NB_B_rad_s = Eigen::Vector3d::Zero();       // [rad/s] estimated body rate
  Eigen::Vector4d wheel_speed_rad_s = Eigen::Vector4d::Zero();  // [rad/s] tachometers, rel. to body
  bool valid = false;  // estimate usable; false → zero torque
};

/// A whole-attitude target instead of the Sun (the local orbital frame of seed S2).
struct AttitudeTargetInput {
  Eigen::Quaterniond q_NB_est = Eigen::Quaterniond::Identity();  // [-] estimated attitude, Hamilton
  Eigen::Quaterniond q_NT = Eigen::Quaterniond::Identity();      // [-] target attitude, Hamilton
  Eigen::Vector3d w_NT_N_rad_s = Eigen::Vector3d::Zero();        // [rad/s] target's rate, inertial
  Eigen::Vector3d w_NB_B_rad_s = Eigen::Vector3d::Zero();        // [rad/s] estimated body rate
  Eigen::Vector4d wheel_speed_rad_s = Eigen::Vector4d::Zero();   // [rad/s] tachometers, rel. to body
  bool valid = false;  // estimate and target usable; false → zero torque
};

/// Seed S2's orbital frame (sim::R_N_S2Orbital) as a target, turning at (r × v)/|r|².
AttitudeTargetInput s2OrbitalTarget(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s);

struct SunPointingControllerOutput {
  Eigen::Vector3d tau_cmd_B_Nm = Eigen::Vector3d::Zero();     // [Nm] torque the wheels put on the body
  Eigen::Vector4d wheel_torque_Nm = Eigen::Vector4d::Zero();  // [Nm] motor torque per wheel (spins it up)
  double pointing_error_rad = 0.0;  // [rad] angle axis ↔ Sun; 0 when !valid
  bool rate_limited = false;        // the P term was limited to ask for max_rate_rad_s
  bool saturated = false;           // |τ| was limited to max_torque_Nm
};

/// Wheel-based Sun pointing of one body axis (ROSAT: +x on the Sun, roll left free).
///
/// τ = k_p·e − k_d·ω + ω × h_w with e = θ·(a × s)/|a × s| the rotation vector taking the axis
/// a onto the Sun s and h_w = Σ a_i I_i Ω_i: the quaternion-feedback regulator of Wie, Weiss &
/// Arapostathis 1989 (J. Guidance 12(3)), u = −K q_e − C ω + ω × (Jω + h), with the
/// angle-scaled error in place of the quaternion vector part and without ω × Jω (J is not a
/// parameter here). The ω × h_w term cancels the gyroscopic coupling of the stored momentum in
/// J ω̇ = −ω × (Jω + h_w) − ḣ_w. For large errors the proportional term is limited so that the
/// rate it commands, k_p/k_d·|e|, stays below max_rate_rad_s — the eigenaxis slew with rate
/// limit of Wie, Bailey & Heiberg 2002 (J. Guidance 25(1)) — which bounds the momentum a slew
/// puts into the wheels. Motor torques τ_m = −A⁺τ, since the body feels −A τ_m.
class SunPointingController {
 public:
  using Params = SunPointingControllerParams;
  using Input = SunPointingControllerInput;
  using Output = SunPointingControllerOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit SunPointingController(const Params& params);

  /// Stateless law: nothing to forget; kept for the common API.
  void reset();

  /// The law does not depend on time; t_ns [ns] is kept for the common API.
  Output step(const Input& in, std::int64_t t_ns);

  /// The same regulator on a whole-attitude target: e is the rotation vector taking the body
  /// onto the target (body axes), the rate term acts on ω − ω_target.
  Output hold(const AttitudeTargetInput& in, std::int64_t t_ns);

  const Params& params() const { return params_; }

 private:
  Output regulate(double angle_rad, const Eigen::Vector3d& axis_B, const Eigen::Vector3d& w_error_B_rad_s,
                  const Eigen::Vector3d& w_NB_B_rad_s, const Eigen::Vector4d& wheel_speed_rad_s) const;

  Params params_;
  Eigen::Matrix<double, 3, 4> A_B_;      // active axes, unused columns zero
  Eigen::Matrix<double, 4, 3> A_pinv_;   // A⁺ of the active axes, unused rows zero
  double max_error_rad_;                 // [rad] |e| at which k_p·|e|/k_d reaches max_rate_rad_s
};

}  // namespace flatsat::attitude_controller
