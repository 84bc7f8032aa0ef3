// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/unloading_controller/Bdot.hpp"

namespace flatsat::unloading_controller {

/// Seed S4 (CN109533396A, algorithms.md S4): spin about a chosen body axis, held on
/// the orbit normal n, with a magnetometer and three coils only.
///
/// The seed's combination of Ḃ and Q = B × ω0 was lost (an image). Settled here:
///
///   P = Ḃ − B × ω_ref,  ω_ref = (ω_s − 2ω0)·a  =  Ḃ − B × (ω_s a) + 2Q,  Q = B × ω0 a,
///   m_i = −m0_i sgn(P_i),
///
/// with a the chosen body axis, ω_s the requested spin rate (inertial, about n) and
/// ω0 the orbital rate. In body axes Ḃ = B × (ω − Ω_f), the field turning at
/// Ω_f ≈ 2ω0 n; so P = B × e with e = ω − Ω_f − ω_ref, the coils' torque τ = m × B
/// gives eᵀτ = −Σ m0_i |P_i| ≤ 0, and at the rest point e = 0 the body spins at ω_s
/// about a = n.
/// Classic B-dot is ω_ref = 0: the rate goes to Ω_f, ≈ 2ω0 about n.
/// Derivation: docs/magnetic_control.md, "The S4 combination, derived".
///
/// Where the field's turn comes from (`field_turn`):
///  - kOrbitRate, the seed's: Ω_f ≈ κω0 n with n taken as a. The real Ω_f is uneven,
///    and the bang-bang law follows it.
///  - kModel: the onboard orbit and field model give ḃ_N, and Bdot takes the field's
///    whole turn out of Ḃ (R̂ from TRIAD of n ↔ a and b_N ↔ B, exact at the rest
///    point a = n). Then P = B × (ω − ω_s a): ω_ref = ω_s a. Sensors are still a
///    magnetometer alone.
/// Why, and how well each does: docs/magnetic_control.md, "Why the seed's form misses
/// 5 orbits, and the field-turn model".
enum class FieldTurn { kOrbitRate, kModel };

/// Which law (`law`):
///  - kCorrected: the combination above, with ω_s, κ and the field turn of `field_turn`.
///  - kSeed: the seed as written, nothing added: Ḃ_k and Q = B_k × ω0 a ([0008],
///    [0012]) combined as P = Ḃ_k − Q = Ḃ_k + ω0 a × B_k, the orbit-rate-compensated
///    B-dot form (ω_ref = ω0 a), the correction at the sample B_k. With the field
///    turning at Ω_f ≈ 2ω0 n its rest point is ω = Ω_f + ω0 a: three turns an orbit
///    about n, the only spin the seed's law can ask for.
enum class SpinLaw { kCorrected, kSeed };

struct SpinCaptureParams {
  Eigen::Vector3d spin_axis_B = Eigen::Vector3d::UnitZ();  // [-] chosen body axis a, unit
  double spin_rate_rad_s = 0.035;                           // [rad/s] ω_s, inertial, about n, finite
  double orbit_rate_rad_s = 1.1e-3;                         // [rad/s] ω0 = 2π / period, > 0
  double field_turn_per_orbit_rate = 2.0;                   // [-] Ω_f / ω0 (2 for near-polar orbits), finite; kOrbitRate
  FieldTurn field_turn = FieldTurn::kOrbitRate;             // [-] where the field's own turn comes from
  SpinLaw law = SpinLaw::kCorrected;                        // [-] the seed as written, or corrected

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;

  /// [rad/s] The inertial spin about the orbit normal the law comes to rest at: ω_s,
  /// or for the seed's law 3ω0 (Ω_f + ω0 with the field's mean turn Ω_f = 2ω0).
  double restRate_rad_s() const { return law == SpinLaw::kSeed ? 3.0 * orbit_rate_rad_s : spin_rate_rad_s; }
};

/// The bang-bang corrected B-dot above for coils of max_dipole_Am2 [A m²]; with
/// kModel, its steps need BdotInput::model (n and the model field).
BdotParams spinCaptureLaw(const SpinCaptureParams& params, const Eigen::Vector3d& max_dipole_Am2);

}  // namespace flatsat::unloading_controller
