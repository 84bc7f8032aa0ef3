// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/common/WheelGeometry.hpp"
#include "components/estimator/FieldFromMomentum.hpp"

namespace flatsat::estimator {

/// Measurement cycle of seed S0: how often, how long, how strong.
struct FieldFromMomentumParams {
  WheelGeometry wheels;            // [-] live wheels, axes, rotor inertias (momentum from the tachometers)
  /// [kg m²] body inertia, wheels locked: the momentum is Σ wheels + J ω (gyro), so torque the
  /// attitude loop has not yet moved into the wheels still counts; zero: wheels only (the seed)
  Eigen::Matrix3d body_inertia_kg_m2 = Eigen::Matrix3d::Zero();
  double quiet_s = 30.0;           // [s] Δt1, no dipole before the pulse, > 0
  double pulse_s = 30.0;           // [s] dipole on-time, > 0
  double settle_s = 0.0;           // [s] no dipole after the pulse, counted with it (the wheels take the impulse), >= 0
  double quiet_after_s = 30.0;     // [s] no dipole after settling (a changing disturbance drops out), >= 0
  double dipole_Am2 = 100.0;       // [A m²] |Mx| asked for on the x coil, > 0
  double cycle_period_s = 600.0;   // [s] from one request to the next, >= the four intervals
  double average_s = 1.0;          // [s] momentum averaging at each instant, >= 0, <= quiet_s / 2
  bool alternate_sign = true;      // [-] flip Mx every cycle so the pulses' impulses cancel
  /// [-] once the field is known, give Mx the sign that unloads the stored wheel momentum
  /// (sign of (H × B)_x, the cross-product law's x coil): the window doubles as an
  /// unloading pulse (the seed reuses unloading pulses as its windows); overrides alternate_sign
  bool unloading_sign = false;
  /// [A m²] > 0: ask the coil owner to hold its unloading law's own dipole as the pulse when
  /// the law drives at least this much along x (and mostly along x) at the pulse start: the
  /// unloading pulse in progress is the window (DE3606636), and the unloading goes on; the
  /// ±Mx pulse otherwise. 0: always ±Mx. >= 0
  double law_pulse_min_Am2 = 0.0;
  double max_sun_offset_rad = 0.0175;  // [rad] a window starts only with body x this close to the Sun, > 0

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// A window the estimator asks the coil owner for.
struct WindowRequest {
  std::uint32_t id = 0;                                // [-] > 0, new per cycle
  Eigen::Vector3d m_B_Am2 = Eigen::Vector3d::Zero();   // [A m²] dipole for the pulse
  double quiet_s = 0.0, pulse_s = 0.0, quiet_after_s = 0.0;  // [s]
  double law_pulse_min_Am2 = 0.0;  // [A m²] as FieldFromMomentumParams (CoilRequest)
};

struct FieldFromMomentumInput {
  Eigen::Vector4d wheel_speed_rad_s = Eigen::Vector4d::Zero();  // [rad/s] tachometers
  bool tach_valid = false;
  Eigen::Vector3d w_B_rad_s = Eigen::Vector3d::Zero();  // [rad/s] gyro
  bool gyro_valid = false;
  Eigen::Vector3d sun_B_unit = Eigen::Vector3d::Zero();  // [-] measured Sun direction
  bool sun_valid = false;
  /// [-] R_SE_N: inertial → Sun-ecliptic frame (X Sun, Y in the ecliptic, Z its pole).
  Eigen::Matrix3d R_SE_N = Eigen::Matrix3d::Identity();
  Eigen::Vector3d b_N_ref_T = Eigen::Vector3d::Zero();  // [T] reference field (field model at the orbit position)
  /// The coil owner's report of a window it finished: its request id and what it applied.
  std::optional<std::pair<std::uint32_t, DipoleWindow>> completed;
  /// The coil owner refused or dropped the request with this id.
  std::optional<std::uint32_t> refused;
};

struct FieldFromMomentumOutput {
  std::optional<WindowRequest> request;  // asserted until the window completes or is refused
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();  // [T] field estimate, body axes, now
  bool valid = false;          // a cycle has succeeded: α and b_B_T are usable
  double alpha_rad = 0.0;      // [rad] roll about the Sun line, α(t) = α(t_ref) + ∫ω_x dt
  std::uint32_t cycles = 0;    // [-] windows solved
  std::uint32_t failed_cycles = 0;  // [-] windows that could not be solved or were refused
  bool solved_now = false;     // a window was solved this step (the fields below are its own)
  Eigen::Vector3d b_cycle_B_T = Eigen::Vector3d::Zero();  // [T] field of the last window (at its t_ref)
  std::int64_t t_cycle_ns = 0;                            // [ns] its t_ref
  double along_dipole_Nm = 0.0;  // [N m] its consistency residual
};

/// Seed S0 (DE3606636 / US4746085; algorithms.md S0) as a cycle: every
/// cycle_period_s it asks the coil owner for a window (quiet, ±Mx pulse, quiet);
/// when the owner reports the window done, FieldFromMomentum gives By, Bz at the
/// pulse's mid-time, and the roll angle about the Sun line follows from the
/// reference field (BX, BY, BZ) in the Sun-ecliptic frame:
///     cos α = (By·BY + Bz·BZ)/(BY² + BZ²),  sin α = (By·BZ − Bz·BY)/(BY² + BZ²)
/// taken with atan2 (the common factor cancels). Between cycles α(t) = α + ∫ω_x dt
/// with the gyro (the seed's α + ω t, with ω measured each step), and the field in
/// body axes is the reference field turned by α: b_B = (BX, BY cos α + BZ sin α,
/// −BY sin α + BZ cos α). Body x is taken on the Sun, as the attitude loop holds it.
/// Bx is never measured: it is BX (the seed: "Bx ... equals the reference BX").
/// A window is asked for only while the Sun sensor sees the Sun on body x.
class FieldFromMomentumEstimator {
 public:
  using Params = FieldFromMomentumParams;
  using Input = FieldFromMomentumInput;
  using Output = FieldFromMomentumOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit FieldFromMomentumEstimator(const Params& params);

  void reset();
  Output step(const Input& in, std::int64_t t_ns);

  const Params& params() const { return params_; }

 private:
  struct Reference {
    std::int64_t t_ns;
    Eigen::Vector3d b_SE_T;  // [T] reference field in the Sun-ecliptic frame
  };
  void solve(const DipoleWindow& window, Output& out);
  const Reference* referenceAt(std::int64_t t_ns) const;
  double keepSeconds() const;

  Params params_;
  FieldFromMomentum field_;
  std::deque<Reference> references_;
  std::optional<WindowRequest> pending_;
  std::uint32_t next_id_ = 1;
  std::int64_t next_request_ns_ = 0;
  bool valid_ = false;
  double alpha_rad_ = 0.0;
  std::int64_t last_t_ns_ = 0;
  bool has_last_ = false;
  Eigen::Vector3d last_w_B_rad_s_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d h_wheels_B_Nms_ = Eigen::Vector3d::Zero();  // [Nms] newest stored momentum
  std::uint32_t cycles_ = 0, failed_ = 0;
  double sign_ = 1.0;
};

/// [rad] Roll about the Sun line from the body field (By, Bz) and the reference
/// field (BY, BZ) in the Sun-ecliptic frame (seed S0); NaN when either is zero.
double s0RollAngle(double by_T, double bz_T, double BY_T, double BZ_T);

/// [T] The reference field b_SE (Sun-ecliptic frame) in body axes at roll α, body x on the Sun.
Eigen::Vector3d s0BodyField(const Eigen::Vector3d& b_SE_T, double alpha_rad);

}  // namespace flatsat::estimator
