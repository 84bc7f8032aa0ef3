// SPDX-License-Identifier: Apache-2.0
#pragma once
// Seed S0 (DE3606636 / US4746085; flatsat spec algorithms.md, S0): the body field
// perpendicular to a known dipole, from the stored momentum alone.

#include <cstdint>
#include <deque>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace flatsat::estimator {

/// One sample of what the estimator measures: stored momentum and body rate.
struct S0MomentumSample {
  std::int64_t t_ns = 0;                             // [ns] sample time
  Eigen::Vector3d h_B_Nms = Eigen::Vector3d::Zero(); // [Nms] stored wheel momentum, body axes
  Eigen::Vector3d w_B_rad_s = Eigen::Vector3d::Zero();  // [rad/s] body rate (gyro)
};

/// A measurement window as the coil owner actually applied it: no dipole over
/// [t0, t1), m over [t1, pulse_end), none over [pulse_end, t2).
struct S0Window {
  std::int64_t t0_ns = 0;         // [ns] quiet interval starts
  std::int64_t t1_ns = 0;         // [ns] dipole on
  std::int64_t pulse_end_ns = 0;  // [ns] dipole off, t1 < pulse_end <= t2
  std::int64_t t2_ns = 0;         // [ns] last measurement
  Eigen::Vector3d m_B_Am2 = Eigen::Vector3d::Zero();  // [A m²] dipole held over the pulse
};

/// What one window tells.
struct S0FieldSolution {
  Eigen::Vector3d b_perp_B_T = Eigen::Vector3d::Zero();  // [T] field ⊥ the dipole, body axes
  Eigen::Vector3d m_unit_B = Eigen::Vector3d::UnitX();   // [-] the dipole's direction
  std::int64_t t_ref_ns = 0;  // [ns] middle of the pulse: the field is its mean over the pulse
  Eigen::Vector3d disturbance_B_Nm = Eigen::Vector3d::Zero();  // [N m] mean external torque, quiet interval
  double along_dipole_Nm = 0.0;  // [N m] torque change along m: zero for a perfect measurement
};

/// The torque a dipole step adds, from the momentum balance in the rotating body
/// frame, dH/dt = T_ext − ω × H (the seed's equations for ω about x):
///
///   ∫T_i = H(end_i) − H(start_i) + ∫_i ω × H dt                    (each interval i)
///   (m·τ_pulse) × B = ∫T_2 − (Δt2/Δt1)·∫T_1                       (constant disturbance cancels)
///   B⊥m = (ΔT × m) / (|m|²·τ_pulse)                               ((m × B) × m = |m|² B⊥m)
///
/// With m = Mx·x̂ and ∫ω × H taken by the rectangle rule this is the seed's
/// By(t0), Bz(t0) with Q2 = 1/(Mx·Δt2), Q21 = Δt2/Δt1, Q31 = Δt3/Δt1. Two departures,
/// each tested: the rotation integral uses every sample (trapezoid) instead of the
/// seed's end values; and the dipole may stop before t2 (pulse_end < t2), leaving
/// the attitude loop time to move the torque from the body into the wheels, so the
/// momentum the wheels show at t2 holds the whole impulse m·τ_pulse × B. The
/// result is the field's mean over the pulse (the seed attributes it to t0: the
/// derivation integrates B over [t1, pulse_end], so its mid-point is the right time).
///
/// Momentum values at t0, t1, t2 are means over `average_s` ending at each instant
/// (tachometer noise falls as 1/√N); for momentum linear in time the mean is the value
/// average_s/2 earlier, the same shift at all three instants, so the formula holds
/// with the shifted instants.
class S0FieldFromMomentum {
 public:
  /// @param average_s [s] averaging span of the momentum at each instant, ≥ 0 (0: one sample)
  explicit S0FieldFromMomentum(double average_s);

  void reset() { samples_.clear(); }

  /// Appends a sample (times increasing); forgets samples older than keep_s [s].
  void add(const S0MomentumSample& sample, double keep_s);

  /// The field of a completed window; none when the window is not covered by
  /// samples, its intervals are empty or the dipole is zero.
  std::optional<S0FieldSolution> solve(const S0Window& window) const;

  /// [rad] Rotation about axis (unit, body) from t_ns to the newest sample: Σ ω·axis dt
  /// over the samples after t_ns (each gyro sample is the mean rate since the one before).
  double angleSince(std::int64_t t_ns, const Eigen::Vector3d& axis) const;

 private:
  struct Point {
    double t_s;                // [s] centroid of the averaged samples
    Eigen::Vector3d h_B_Nms;   // [Nms] their mean
  };
  std::optional<Point> meanBefore(std::int64_t t_ns) const;
  Eigen::Vector3d rotationIntegral(double from_s, double to_s) const;  // ∫ ω × H dt [N m s]

  double average_s_;
  std::deque<S0MomentumSample> samples_;
};

}  // namespace flatsat::estimator
