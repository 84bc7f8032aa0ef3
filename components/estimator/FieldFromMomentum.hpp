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
struct MomentumSample {
  std::int64_t t_ns = 0;                             // [ns] sample time
  Eigen::Vector3d h_B_Nms = Eigen::Vector3d::Zero(); // [Nms] angular momentum, body axes (wheels, or wheels + J ω)
  Eigen::Vector3d w_B_rad_s = Eigen::Vector3d::Zero();  // [rad/s] body rate (gyro)
};

/// A measurement window as the coil owner actually applied it: no dipole over
/// [t0, t1), m over [t1, pulse_end), none over [pulse_end, t2).
struct DipoleWindow {
  std::int64_t t0_ns = 0;         // [ns] quiet interval before the pulse starts
  std::int64_t t1_ns = 0;         // [ns] dipole on
  std::int64_t pulse_end_ns = 0;  // [ns] dipole off, t1 < pulse_end <= t2
  std::int64_t t2_ns = 0;         // [ns] end of the quiet interval after the pulse (= pulse_end: none)
  Eigen::Vector3d m_B_Am2 = Eigen::Vector3d::Zero();  // [A m²] dipole held over the pulse
};

/// What one window tells.
struct FieldSolution {
  Eigen::Vector3d b_perp_B_T = Eigen::Vector3d::Zero();  // [T] field ⊥ the dipole, body axes
  Eigen::Vector3d m_unit_B = Eigen::Vector3d::UnitX();   // [-] the dipole's direction
  std::int64_t t_ref_ns = 0;  // [ns] middle of the pulse: the field is its mean over the pulse
  Eigen::Vector3d disturbance_B_Nm = Eigen::Vector3d::Zero();  // [N m] external torque during the pulse (interpolated)
  double along_dipole_Nm = 0.0;  // [N m] torque change along m: zero for a perfect measurement
};

/// The torque a dipole step adds, from the momentum balance in the rotating body
/// frame, dH/dt = T_ext − ω × H (seed S0, DE3606636). For each interval i (quiet
/// before A, pulse P, quiet after C):
///
///   ∫T_i = H(end_i) − H(start_i) + ∫_i ω × H dt
///   (m·τ_P) × B = ∫T_P − d_P·τ_P,   B⊥m = (ΔT × m) / (|m|²·τ_P)
///
/// with d_P the disturbance during the pulse (from A alone, or A and C interpolated
/// to the pulse's mid-time). The result is the field's mean over the pulse. The
/// seed's closed form as a special case, the departures from it and the momentum
/// means at each instant: docs/s0_study.md, "The momentum balance, derived".
class FieldFromMomentum {
 public:
  /// @param average_s [s] averaging span of the momentum at each instant, ≥ 0 (0: one sample),
  ///        at most half the quiet intervals
  explicit FieldFromMomentum(double average_s);

  void reset() { samples_.clear(); }

  /// Appends a sample (times increasing); forgets samples older than keep_s [s].
  void add(const MomentumSample& sample, double keep_s);

  /// The field of a completed window; none when the window is not covered by
  /// samples, its intervals are empty or the dipole is zero.
  /// @param settle_s [s] quiet time after the pulse still counted with it (the attitude
  ///        loop moving the pulse's momentum into the wheels); the rest of the quiet
  ///        interval after it measures the disturbance again.
  std::optional<FieldSolution> solve(const DipoleWindow& window, double settle_s = 0.0) const;

  /// [rad] Rotation about axis (unit, body) from t_ns to the newest sample: Σ ω·axis dt
  /// over the samples after t_ns (each gyro sample is the mean rate since the one before).
  double angleSince(std::int64_t t_ns, const Eigen::Vector3d& axis) const;

 private:
  struct Point {
    double t_s;                // [s] centroid of the averaged samples
    Eigen::Vector3d h_B_Nms;   // [Nms] their mean
  };
  std::optional<Point> meanOver(std::int64_t from_ns, std::int64_t to_ns) const;
  Eigen::Vector3d rotationIntegral(double from_s, double to_s) const;  // ∫ ω × H dt [N m s]

  double average_s_;
  std::deque<MomentumSample> samples_;
};

}  // namespace flatsat::estimator
