// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "components/station_keeping/GeoElements.hpp"

namespace flatsat::station_keeping {

struct MeanElementsParams {
  double window_s = 86164.0905;  ///< [s] one sidereal day, what the daily oscillations repeat over, [3600, 864000]
};

/// Every problem with `params`, naming the field and its range; empty: valid.
std::vector<std::string> validate(const MeanElementsParams& params);

/// The mean synchronous elements of each window from the osculating ones:
/// e and i averaged, which removes what turns with the spacecraft (the J2 and
/// lunar-solar terms of one orbit), and the drift and longitude from a
/// least-squares fit of the longitude, as an orbit determination gives them:
/// a line plus the harmonics of one and two cycles a window. Without the
/// harmonics the line takes up part of the longitude's daily and half-daily
/// swing under the Sun and Moon as drift (the 20/30 failure's longitude
/// excursion over a year grew from 0.036° to 0.049°).
/// The fit matters: at GEO the osculating semi-major axis under J2 is not the
/// one of the mean motion (Δn/n ≈ 1.5 J2 (R/a)² = 3.7e-5), which read as a
/// drift would walk the longitude by about 0.01°/day.
class MeanElementsFilter {
 public:
  /// @throws std::invalid_argument naming the field.
  explicit MeanElementsFilter(const MeanElementsParams& params);
  void reset();
  /// Takes the osculating elements at t_s [s]; the mean of the window that
  /// ends with this sample when it is complete (longitude at t_s), else nothing.
  std::optional<SynchronousElements> step(const SynchronousElements& osculating, double t_s);
  /// A firing of this window, with its (linear) effect, given at t_s: the
  /// samples before it are counted as if it had been given before them, so
  /// the mean is that of the orbit after it (orbit determination that knows
  /// its own manoeuvres). Without it, a window's mean would still hold the
  /// inclination the firing removed, and a radial firing's longitude jump
  /// would read as drift.
  void impulse(const ImpulseEffect& effect, double t_s);

 private:
  MeanElementsParams params_;
  std::optional<double> start_s_;
  int count_ = 0;
  double last_longitude_ = 0.0, unwrapped_ = 0.0;
  Eigen::Vector2d i_sum_{0.0, 0.0}, e_sum_{0.0, 0.0};
  double a_sum_ = 0.0;
  // Least squares of the longitude (with the drift the firings added taken
  // out again) on a line in time plus the daily and half-daily harmonics.
  Eigen::Matrix<double, 6, 6> normal_ = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> moment_ = Eigen::Matrix<double, 6, 1>::Zero();
  double added_drift_ = 0.0;    // [rad/s] the sum of the firings' drift changes
  double added_moment_ = 0.0;   // [rad] Σ Δdrift_k t_k, so the added longitude is added_drift_ t − added_moment_
  double added_jump_ = 0.0;     // [rad] Σ Δl_k, the jumps of the radial firings
};

}  // namespace flatsat::station_keeping
