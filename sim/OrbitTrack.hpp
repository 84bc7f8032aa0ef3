// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/KeplerOrbit.hpp"
#include "sim/OrbitForces.hpp"
#include "sim/OrbitPropagator.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {

/// How the spacecraft's centre of mass moves.
enum class OrbitPropagation {
  kKepler,     // two-body, closed form (KeplerOrbit); thrust does not move it
  kNumerical,  // OrbitPropagator (DOP853) under OrbitForces, on its own time grid
};

struct OrbitTrackParams {
  OrbitPropagation propagator = OrbitPropagation::kKepler;
  OrbitForceParams forces;  // kNumerical: forces and the spacecraft's mass, areas, coefficients
  double step_s = 10.0;     // [s] kNumerical: integration step, in (0, 600]

  /// Every violation as "field: reason" (forces only checked for kNumerical).
  std::vector<std::string> validate() const;
};

/// The orbit of the dynamics model, decoupled from the attitude step.
///
/// kNumerical integrates on the grid t_j = j·step_s (from the epoch) and returns
/// the cubic Hermite interpolant of the two bracketing states (position and
/// velocity at both ends) inside a grid interval, so the attitude step needs no
/// relation to step_s. Interpolation error for a near-circular orbit, whose
/// fourth derivative is |r⁽⁴⁾| ≈ n⁴ r (n the mean motion): position ≤ h⁴ |r⁽⁴⁾| / 384,
/// velocity ≈ h³ |r⁽⁴⁾| / 125 — at 560 km (|r⁽⁴⁾| ≈ 1.0e-5 m/s⁴) and h = 10 s,
/// 0.3 mm and 0.1 mm/s; at h = 60 s, 0.3 m and 2 cm/s — well below the force
/// models' own errors. Holding the position instead would be off by v·h (76 km at
/// 10 s). The integrator's own error at 10 s is below 1 mm per orbit.
/// A kick (thrust) integrates from the interval's start to the kick, adds the kick,
/// and integrates on to the next grid point, so the grid stays fixed (two
/// integrator steps per kick; the interpolant's errors never enter the orbit).
class OrbitTrack {
 public:
  using State = KeplerOrbit::State;

  /// @throws std::invalid_argument listing every violation of params and elements.
  OrbitTrack(const OrbitTrackParams& params, const OrbitElements& elements, const UtcEpoch& epoch);

  /// Back to the elements' state at t = 0.
  void reset();

  /// State at t_s [s] after the epoch. kNumerical integrates forward as far as
  /// needed; a time before the current grid interval (or before the last kick)
  /// extrapolates the interval's interpolant, so callers ask in increasing time.
  /// Never throws, never allocates.
  State at(double t_s);

  /// Adds dr_N_m [m] and dv_N_m_s [m/s] to the state at t_s [s] (kNumerical; Kepler
  /// ignores it). Never throws, never allocates.
  void kick(double t_s, const Eigen::Vector3d& dr_N_m, const Eigen::Vector3d& dv_N_m_s);

  const OrbitTrackParams& params() const { return params_; }

 private:
  struct Node {
    double t_s;
    State state;
  };
  void advance();  // the next grid interval

  OrbitTrackParams params_;
  KeplerOrbit kepler_;
  std::optional<OrbitPropagator> propagator_;  // kNumerical; sits at end_
  long long end_index_ = 0;                    // end_.t_s = end_index_ · step_s
  Node start_;
  Node end_;
};

}  // namespace flatsat::sim
