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
/// ω0 the orbital rate. Derivation:
///  1. In body axes Ḃ = R_BN ḃ_N − ω × B. The field's direction turns in inertial
///     space: on a near-polar orbit the dipole field B ∝ cos u·t̂ − 2 sin u·r̂ (u the
///     argument of latitude, t̂ north, r̂ up) turns twice per orbit, in the sense of
///     the orbit (3ω0 over the equator, 1.5ω0 over the poles, 2ω0 on average), so
///     ḃ_N ≈ Ω_f × b_N with Ω_f ≈ 2ω0 n, and Ḃ = B × (ω − Ω_f).
///  2. Hence P = B × e with e = ω − Ω_f − ω_ref, and the coil torque τ = m × B obeys
///     eᵀτ = mᵀ(B × e) = mᵀP = −Σ m0_i |P_i| ≤ 0: the bang-bang law can only shrink
///     the part of e across B, and the orbit turns B, so all of e goes.
///  3. The rest point e = 0 is ω = ω_ref + Ω_f = (ω_s − 2ω0) a + 2ω0 n. A rigid body
///     turning steadily has a fixed rate in body axes, so n must be fixed in body
///     axes too: ω ∥ n ∥ a, and with a = n the spin is ω_s about n. The minus sign
///     in P = Ḃ − B × ω_ref is what makes step 2 dissipative (with +, the rest point
///     is ω = −ω_ref + Ω_f and the law spins the body the wrong way).
///  4. The orbital term is 2ω0, not ω0: Ḃ measures the body's turn relative to the
///     field, and the field turns at 2ω0. With ω0 (the reading "spin + orbital rate"
///     of ω_ref) the rate settles ω0 high: 3 % of a 2 deg/s spin at 550 km; with no
///     orbital term, 2ω0 high (6 %). The closed-loop tests ([bdot]) and `flatsat
///     study spin` check the rate against ω_s itself.
/// Classic B-dot is ω_ref = 0: the rate goes to Ω_f, ≈ 2ω0 about n.
///
/// Where the field's turn comes from (`field_turn`):
///  - kOrbitRate, the seed's: Ω_f ≈ κω0 n with n taken as a. The real Ω_f is uneven
///    (1.5ω0 to 3ω0 along n, and across n where the dipole's tilt and the higher
///    harmonics bend the field), and the bang-bang law follows it: on s4_spin.yaml
///    (IGRF degree 10) the spin axis wanders 0-9 deg and the rate ±4 % within each
///    orbit, and 5 deg / 5 % are held only from about 5.9 orbits on (docs/magnetic_control.md).
///  - kModel: the onboard orbit and field model give ḃ_N, and Bdot takes the field's
///    whole turn out of Ḃ (R̂ from TRIAD of n ↔ a and b_N ↔ B, exact at the rest
///    point a = n). Then P = B × (ω − ω_s a): ω_ref = ω_s a. Away from the rest
///    point R̂ is off by the tilt of a from n, and that residual, like the seed's
///    κω0(n − a), is what turns a onto n. Sensors are still a magnetometer alone.
enum class FieldTurn { kOrbitRate, kModel };

struct SpinCaptureParams {
  Eigen::Vector3d spin_axis_B = Eigen::Vector3d::UnitZ();  // [-] chosen body axis a, unit
  double spin_rate_rad_s = 0.035;                           // [rad/s] ω_s, inertial, about n, finite
  double orbit_rate_rad_s = 1.1e-3;                         // [rad/s] ω0 = 2π / period, > 0
  double field_turn_per_orbit_rate = 2.0;                   // [-] Ω_f / ω0 (2 for near-polar orbits), finite; kOrbitRate
  FieldTurn field_turn = FieldTurn::kOrbitRate;             // [-] where the field's own turn comes from

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// The bang-bang corrected B-dot above for coils of max_dipole_Am2 [A m²]; with
/// kModel, its steps need BdotInput::model (n and the model field).
BdotParams spinCaptureLaw(const SpinCaptureParams& params, const Eigen::Vector3d& max_dipole_Am2);

}  // namespace flatsat::unloading_controller
