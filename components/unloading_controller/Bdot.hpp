// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace flatsat::unloading_controller {

/// How the dipole follows P.
enum class BdotShape {
  kBangBang,      // m_i = −m0_i sgn(P_i): the seed S4 output (CN109533396A claim 6)
  kProportional,  // m = −k P, each coil clipped to ±m0_i
};

struct BdotParams {
  BdotShape shape = BdotShape::kBangBang;  // [-] output shape
  double gain_Am2_s_per_T = 1.0e6;  // [A m² s/T] k of kProportional, > 0
  Eigen::Vector3d max_dipole_Am2 = Eigen::Vector3d::Constant(0.2);  // [A m²] per-coil limit m0_i, > 0
  Eigen::Vector3d omega_ref_B_rad_s = Eigen::Vector3d::Zero();  // [rad/s] ω_ref; 0: classic B-dot, finite
  double filter_time_constant_s = 0.0;  // [s] first-order low-pass on Ḃ, 0: none, >= 0
  double deadband_rad_s = 0.0;  // [rad/s] coil i off while |P_i| < |B|·deadband, >= 0
  double max_sample_gap_s = 10.0;  // [s] a longer gap between usable samples restarts the difference, > 0
  double min_field_T = 1.0e-6;  // [T] |B| below this: sample unusable, > 0
  /// [-] true: the correction B × ω_ref at the newest sample B_k, the seed's B_b
  /// (CN109533396A [0012]); false: at the secant's midpoint (see step()).
  bool correction_at_sample = false;

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// What an onboard orbit and field model know of the field's own motion: the
/// model field and one direction known both in inertial and in body axes.
struct BdotModelField {
  Eigen::Vector3d b_N_T = Eigen::Vector3d::Zero();             // [T] model field at the spacecraft, inertial
  Eigen::Vector3d axis_N_unit = Eigen::Vector3d::UnitZ();      // [-] a direction in inertial axes, unit
  Eigen::Vector3d axis_B_unit = Eigen::Vector3d::UnitZ();      // [-] the same direction in body axes, unit
};

struct BdotInput {
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();  // [T] measured field, body axes
  bool b_valid = false;                             // field usable
  /// When set, Ḃ loses the field's own turn: Ḃ − R̂ ḃ_N = B × ω (see Bdot::step).
  /// Given at every step or at none: a step without it restarts the difference.
  std::optional<BdotModelField> model;
};

struct BdotOutput {
  Eigen::Vector3d m_B_Am2 = Eigen::Vector3d::Zero();        // [A m²] dipole command
  Eigen::Vector3d b_dot_B_T_s = Eigen::Vector3d::Zero();    // [T/s] Ḃ after the low-pass
  Eigen::Vector3d p_B_T_s = Eigen::Vector3d::Zero();        // [T/s] P = Ḃ − B × ω_ref
  /// [rad/s] |P|/|B| = |(ω − ω_ref − Ω_field)⊥B|: the rate error the law can see
  /// (for B-dot, the body's rate across the field); nullopt before the first Ḃ.
  std::optional<double> rate_error_rad_s;
  bool active = false;     // a dipole is commanded this step (Ḃ known, field usable)
  bool saturated = false;  // at least one coil at its limit
};

/// Corrected B-dot (algorithms.md S4; seed CN109533396A): Ḃ_k = (B_k − B_{k−1})/Δt,
/// optionally low-passed, P = Ḃ − B × ω_ref, dipole −m0 sgn(P_i) or −k P per coil.
///
/// Why it damps: the body sees the field turn as Ḃ = B × (ω − Ω_f) with Ω_f the
/// field direction's own inertial turn rate (≈ 2ω0 about the orbit normal on a
/// near-polar orbit). With e = ω − Ω_f − ω_ref, P = B × e and the torque
/// τ = m × B. Proportional: τ = −k (B × e) × B = −k |B|² e⊥B. Bang-bang:
/// eᵀτ = mᵀ(B × e) = mᵀP = −Σ m0_i |P_i| ≤ 0. Either way the kinetic energy of the
/// rate error, ½ eᵀJe, cannot grow while Ω_f and ω_ref are slow next to the body
/// rate. Classic B-dot (ω_ref = 0; Stickler & Alfriend, "Elementary magnetic
/// attitude control system", J. Spacecraft 13(5), 1976) removes the body's kinetic
/// energy: dE/dt = ωᵀτ = −k|B × ω|² (or −Σ m0_i|Ḃ_i|) up to the Ω_f term.
/// Per-coil clipping keeps the sign of every term, so each still dissipates.
class Bdot {
 public:
  using Params = BdotParams;
  using Input = BdotInput;
  using Output = BdotOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit Bdot(const Params& params);

  /// Forgets the previous sample and the filter.
  void reset();

  /// One control period at t_ns [ns]: Δt is the time since the previous usable sample.
  Output step(const Input& in, std::int64_t t_ns);

  const Params& params() const { return params_; }

 private:
  Params params_;
  std::optional<Eigen::Vector3d> previous_b_B_T_;
  std::optional<Eigen::Vector3d> previous_b_N_T_;  // model field at the previous sample
  std::int64_t previous_t_ns_ = 0;
  std::optional<Eigen::Vector3d> b_dot_B_T_s_;  // low-passed
};

}  // namespace flatsat::unloading_controller
