// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <Eigen/Core>

#include "sim/KeplerOrbit.hpp"
#include "sim/OrbitForces.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {

/// Numerical orbit propagation in the inertial frame N under OrbitForces.
///
/// Integrator: the 8th-order Runge–Kutta formula of Dormand & Prince's DOP853
/// (Hairer, Nørsett & Wanner, Solving ODEs I, 2nd ed., §II.10), 12 stages, used at a
/// fixed step without its error estimators: the global error falls as dt⁸.
/// The Sun and the Moon are evaluated once per step, at its end, and interpolated
/// linearly across the step's stages — less than 2 m of lunar position at a 60 s step,
/// far below the ephemerides' own error.
/// Time scales: the epoch is UTC; TT = UTC + OrbitForceParams::tt_minus_utc_s.
class OrbitPropagator {
 public:
  using State = KeplerOrbit::State;

  /// @throws std::invalid_argument listing every violation of params or epoch, or a
  ///         non-finite initial state or one inside the Earth.
  OrbitPropagator(const OrbitForceParams& params, const UtcEpoch& epoch, const State& initial);

  /// State at time_s().
  const State& state() const { return state_; }
  /// [s] since the epoch.
  double time_s() const { return t_s_; }

  /// Restarts from `state` at t_s [s] after the epoch (an impulse, a reset). Never
  /// throws, never allocates; the state is not checked.
  void restart(double t_s, const State& state);

  /// Advances by dt_s [s] (negative goes back) in one step. A zero or non-finite dt_s
  /// changes nothing. Never throws, never allocates.
  void step(double dt_s);

  /// [m/s²] Acceleration of state at t_s [s] after the epoch, ephemerides evaluated at t_s.
  Eigen::Vector3d acceleration_N(double t_s, const State& state) const;

 private:
  double jdTt(double t_s) const;

  OrbitForces forces_;
  double jd_tt_epoch_;  // [d] Julian date (TT) of t = 0
  double t_s_ = 0.0;
  State state_;
  Ephemerides bodies_;  // at t_s_
};

}  // namespace flatsat::sim
