// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace flatsat::sim {

inline constexpr int kMaxWheels = 4;

/// Rigid spacecraft with up to kMaxWheels reaction wheels; the first wheel_count
/// columns/entries describe the fitted wheels, the rest are ignored.
struct RigidBodyParams {
  Eigen::Matrix3d J_B_kg_m2 = Eigen::Matrix3d::Identity();  // [kg m²] total, wheels locked; SPD, triangle inequality
  int wheel_count = 0;                                      // [-] 0..kMaxWheels
  // [-] unit spin axes a_i, one per column
  Eigen::Matrix<double, 3, kMaxWheels> wheel_axes_B = Eigen::Matrix<double, 3, kMaxWheels>::Zero();
  Eigen::Vector4d wheel_inertia_kg_m2 = Eigen::Vector4d::Zero();  // [kg m²] rotor axial inertia I_w, > 0
  Eigen::Vector4d wheel_max_torque_Nm = Eigen::Vector4d::Zero();  // [N m] motor torque limit, > 0
  // [N m s] limit of I_w Ω, the momentum relative to the body, > 0
  Eigen::Vector4d wheel_max_momentum_Nms = Eigen::Vector4d::Zero();
  Eigen::Vector4d wheel_viscous_friction_Nms_rad = Eigen::Vector4d::Zero();  // [N m s/rad] c_v, bearing drag, ≥ 0
  Eigen::Vector4d wheel_coulomb_friction_Nm = Eigen::Vector4d::Zero();       // [N m] c_c, dry friction, ≥ 0

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct RigidBodyState {
  Eigen::Quaterniond q_NB = Eigen::Quaterniond::Identity();  // body → inertial
  Eigen::Vector3d w_NB_B = Eigen::Vector3d::Zero();          // [rad/s] body rate
  Eigen::Vector4d h_wheels_Nms = Eigen::Vector4d::Zero();    // [N m s] absolute axial momentum, I_w (Ω_i + a_iᵀω)
};

/// Gyrostat dynamics. With A = [a_1 … a_n] the wheel axes, h the absolute axial
/// wheel momenta, J' = J − Σ I_w a_i a_iᵀ the inertia without the rotors' spin:
///   H_B = J'ω + A h                      (body-frame total angular momentum)
///   Ḣ_N = τ_ext  ⇒  J'ω̇ + A ḣ + ω × H_B = τ_ext          (transport theorem)
///   ḣ_i = τ_m,i + τ_f,i  (balanced, axisymmetric rotors: motor and bearing
///                friction are the only axial torques on rotor i)
///   ⇒ J'ω̇ = τ_ext − ω × (J'ω + A h) − A (τ_m + τ_f),  q̇ = ½ q ⊗ (0, ω).
/// (Wertz, Spacecraft Attitude Determination and Control, Eq. 16-54, with the
/// wheel momentum split into its absolute axial part.)
///
/// Friction on rotor i at relative speed Ω: τ_f = −c_v Ω − c_c sgn Ω. The sign
/// function is replaced by the ramp Ω / Ω_ε inside a band |Ω| < Ω_ε, with
/// Ω_ε = c_c h / I_eff the speed dry friction alone takes from the free wheel in
/// one substep h (1/I_eff = 1/I_w + aᵀJ'⁻¹a; the body's reaction included). In
/// the band a coasting wheel obeys I_eff Ω̇ = −(c_c/Ω_ε + c_v) Ω, λh = −1 − c_v h/I_eff,
/// and RK4's factor per substep stays in (0, 1) for λh down to −2.78: the wheel
/// creeps to rest without reversing or chattering — the limit-cycle fix of
/// Basilisk's ReactionWheelStateEffector (omegaLimitCycle), with the band sized
/// to the step. The price: a motor torque |τ_m| < c_c at rest turns the wheel at
/// the creep speed τ_m Ω_ε / c_c instead of holding it. Outside the band the law
/// is exact, so a coasting wheel follows the closed form of
/// I_eff Ω̇ = −c_v Ω − c_c sgn Ω until |Ω| reaches Ω_ε.
class RigidBodyWheels {
 public:
  /// Params must be valid (RigidBodyParams::validate() empty).
  explicit RigidBodyWheels(const RigidBodyParams& params);

  const RigidBodyParams& params() const { return params_; }

  /// State with wheel speeds Ω [rad/s] relative to the body instead of momenta.
  RigidBodyState makeState(const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& w_NB_B,
                           const Eigen::Vector4d& wheel_speeds_rad_s) const;

  /// [rad/s] Ω_i = h_i / I_w − a_iᵀω; zero for absent wheels.
  Eigen::Vector4d wheelSpeeds_rad_s(const RigidBodyState& x) const;
  /// [N m s] Σ a_i I_w Ω_i: the wheels' momentum relative to the body.
  Eigen::Vector3d wheelMomentum_B_Nms(const RigidBodyState& x) const;
  /// [N m s] Total angular momentum of body and wheels in the inertial frame.
  Eigen::Vector3d totalMomentum_N_Nms(const RigidBodyState& x) const;
  /// The state with attitude q_NB and rate w_NB_B set and the wheels holding
  /// the rest of the total momentum H_N_Nms [N m s]: A h = R_BN H_N − J'ω, in
  /// the least-squares sense when the wheels do not span three axes (what an
  /// ideal attitude controller leaves them with).
  RigidBodyState heldAt(const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& w_NB_B,
                        const Eigen::Vector3d& H_N_Nms) const;
  /// [J] ½ωᵀJ'ω + Σ h_i²/(2 I_w).
  double kineticEnergy_J(const RigidBodyState& x) const;

  /// [N m] Friction torque on each rotor, τ_f = −c_v Ω − c_c sat(Ω / Ω_ε), with the
  /// band Ω_ε set by the RK4 substep substep_s [s] (see the class comment; 0 gives
  /// the bare sign function, sgn 0 = 0); zero for absent wheels.
  Eigen::Vector4d frictionTorque_Nm(const RigidBodyState& x, double substep_s) const;

  /// [N m] Command clamped to ±max torque, zeroed where it would drive a wheel's
  /// relative momentum I_w Ω further past its limit, zero for absent wheels and
  /// non-finite commands.
  Eigen::Vector4d limitMotorTorque(const RigidBodyState& x, const Eigen::Vector4d& tau_cmd_Nm) const;

  /// Advances x from t0_s by dt_s [s] with the motor torques [N m] held, in
  /// `substeps` ≥ 1 steps of classical RK4. Stages see a normalised quaternion
  /// (the field extended as f(q/|q|), same solutions on the unit sphere) and each
  /// substep ends with a projection back onto it (Hairer, Lubich & Wanner,
  /// Geometric Numerical Integration, §IV.4, standard projection method); both
  /// keep RK4's order 4. Wheel friction acts at every stage (frictionTorque_Nm
  /// with the substep). tau_ext_B_Nm(t_s, state) -> Eigen::Vector3d [N m].
  template <class TorqueFn>
  RigidBodyState propagate(const RigidBodyState& x, double t0_s, double dt_s, int substeps,
                           const Eigen::Vector4d& tau_motor_Nm, TorqueFn&& tau_ext_B_Nm) const;

 private:
  struct Derivative {
    Eigen::Vector4d q_dot;  // quaternion coefficients (x, y, z, w) per second
    Eigen::Vector3d w_dot;  // [rad/s²]
    Eigen::Vector4d h_dot;  // [N m]
  };

  Derivative derivative(const RigidBodyState& x, const Eigen::Vector3d& tau_ext_B_Nm,
                        const Eigen::Vector4d& tau_motor_Nm, double substep_s) const;
  /// x + dt·k with the quaternion renormalised.
  static RigidBodyState advanced(const RigidBodyState& x, const Derivative& k, double dt_s);
  /// RK4 weights: (k1 + 2 k2 + 2 k3 + k4) / 6.
  static Derivative rk4Average(const Derivative& k1, const Derivative& k2, const Derivative& k3, const Derivative& k4);

  RigidBodyParams params_;
  Eigen::Vector4d active_;                  // 1 for fitted wheels, 0 otherwise
  Eigen::Matrix<double, 3, kMaxWheels> A_;  // axes of fitted wheels, zero columns otherwise
  Eigen::Matrix<double, kMaxWheels, 3> A_pinv_;  // its pseudo-inverse (heldAt's least squares)
  Eigen::Vector4d inertia_;                 // [kg m²] I_w of fitted wheels, 0 otherwise
  Eigen::Vector4d viscous_;                 // [N m s/rad] c_v of fitted wheels, 0 otherwise
  Eigen::Vector4d coulomb_;                 // [N m] c_c of fitted wheels, 0 otherwise
  Eigen::Vector4d inverse_effective_inertia_;  // [1/(kg m²)] 1/I_w + aᵀJ'⁻¹a, 0 for absent wheels
  Eigen::Matrix3d J_spinless_;              // [kg m²] J'
  Eigen::Matrix3d J_spinless_inv_;          // [1/(kg m²)]
};

template <class TorqueFn>
RigidBodyState RigidBodyWheels::propagate(const RigidBodyState& x, double t0_s, double dt_s, int substeps,
                                          const Eigen::Vector4d& tau_motor_Nm, TorqueFn&& tau_ext_B_Nm) const {
  const double h = dt_s / substeps;
  const auto f = [&](double t_s, const RigidBodyState& s) {
    return derivative(s, tau_ext_B_Nm(t_s, s), tau_motor_Nm, h);
  };
  RigidBodyState state = x;
  state.q_NB.normalize();
  for (int i = 0; i < substeps; ++i) {
    const double t = t0_s + i * h;
    const Derivative k1 = f(t, state);
    const Derivative k2 = f(t + 0.5 * h, advanced(state, k1, 0.5 * h));
    const Derivative k3 = f(t + 0.5 * h, advanced(state, k2, 0.5 * h));
    const Derivative k4 = f(t + h, advanced(state, k3, h));
    state = advanced(state, rk4Average(k1, k2, k3, k4), h);
  }
  return state;
}

}  // namespace flatsat::sim
