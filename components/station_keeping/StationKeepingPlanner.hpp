// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "components/station_keeping/FiringTable.hpp"
#include "components/station_keeping/GeoElements.hpp"
#include "components/station_keeping/GeoThrusters.hpp"

namespace flatsat::station_keeping {

struct StationKeepingParams {
  double station_longitude_rad = 0.0;  ///< [rad] east of Greenwich, [−π, π]
  double longitude_return_s = 259200.0;  ///< [s] the time constant of the drift that brings the longitude back, [1 d, 60 d]
  GeoThrusterParams thrusters;
  double thrust_N = 0.165;      ///< [N] per thruster, (0, 2]
  double mass_kg = 2000.0;      ///< [kg] (0, 1e5]
  double max_burn_s = 14400.0;  ///< [s] per firing, [60, 43200]: an arc of at most ±30° of orbit at 4 h
  double max_ra_shift_rad = 0.52;  ///< [rad] how far the i firings may move from 90°/270°, [0, π/4]
  /// [rad] each firing the table gives to MD is flown as two halves this far
  /// either side of its centre, [0, π/6]: see step().
  double dump_arc_rad = 0.2618;
  // The station box, by which the plan weighs what it cannot correct at once.
  double box_longitude_rad = 8.7266e-4;    ///< [rad] ± half-width (0.05°), (0, 0.0175]
  double box_inclination_rad = 8.7266e-4;  ///< [rad] (0.05°), (0, 0.0175]
  double box_eccentricity = 2e-4;          ///< [-] (0, 0.01]
  /// [s] a drift error weighs as the longitude it makes in this time, [1 d, 60 d]:
  /// longer holds the longitude tighter at the cost of i and e (in the
  /// outer-pair failures, where one firing carries drift, e and some i).
  double drift_horizon_s = 345600.0;
  /// Failure modes 2 and 3 (20/30 or 24/26 failed): true, NC(22) and SC(28)
  /// fire equally, as the seed has them, so that their radial parts cancel;
  /// false (default), each sized on its own. Equal holds the box next to the
  /// stable point (75°E) on 17 % less ΔV but leaves it where J22 drives the
  /// longitude (105°E, 19.2°E), where each on its own holds it or comes nearest
  /// (docs/s3_station_keeping.md).
  bool centre_pair_equal = false;
};

/// Every problem with `params`, naming the field and its range; empty: valid.
std::vector<std::string> validate(const StationKeepingParams& params);

/// One firing of the plan for the next orbit.
struct PlannedFiring {
  GeoThruster thruster = GeoThruster::kNW;
  double ra_rad = 0.0;      ///< [rad] right ascension of the firing's centre, [0, 2π)
  double dv_m_s = 0.0;      ///< [m/s] along the thruster's force direction, ≥ 0
  double duration_s = 0.0;  ///< [s] dv · mass / thrust
  Job job = Job::kInclinationDriftEccentricity;
};

struct StationKeepingInputs {
  SynchronousElements mean;      ///< averaged over the last orbit
  PairFailure failure = PairFailure::kNone;
  Eigen::Vector3d sun_N_unit{1.0, 0.0, 0.0};  ///< the Sun's direction, inertial
  /// [m/s] per firing of the momentum-dump pair (22/28 in the nominal table;
  /// each of the pair gets it so that their radial parts cancel), ≥ 0.
  double dump_dv_m_s = 0.0;
};

struct StationKeepingPlan {
  std::vector<PlannedFiring> firings;
  /// The synchronous elements the plan leaves by first-order effects: what the
  /// table's thrusters could not correct shows here.
  Eigen::Vector2d i_after{0.0, 0.0};
  Eigen::Vector2d e_after{0.0, 0.0};
  double drift_after_rad_s = 0.0;
  double drift_target_rad_s = 0.0;  ///< [rad/s] what brings the longitude (after the jumps) back to the station
  double longitude_jump_rad = 0.0;  ///< [rad] how far the firings' radial parts move the mean longitude
  double dv_total_m_s = 0.0;
  Season season;
};

/// Once an orbit: the firings of the seed's Table I for the state and season
/// (FiringTable.hpp), each sized so that together they bring the inclination
/// and eccentricity vectors to zero and the drift to the one that returns the
/// longitude to the station in `longitude_return_s`, as far as the available
/// thrusters can. Each error is weighed by its share of the box (a drift
/// error by the longitude it makes in drift_horizon_s), so that when the firings cannot
/// meet all three the one with the most room gives. The effects are linear
/// (GeoElements.hpp impulseEffect); the sizes are the non-negative least
/// squares solution (Lawson & Hanson, Solving
/// Least Squares Problems, 1974, ch. 23), exact over all subsets of the at
/// most six firings. The i firings move off 90°/270° (at most
/// max_ra_shift_rad, in steps of 2.5°) by the shift that leaves the least
/// error, "approximately 90° RA" in the seed's words.
///
/// A firing the table gives to MD is flown as two halves at its centre ±
/// dump_arc_rad (δ): their thrust lines part by about 2 sin θ sin δ (θ the
/// cant), so together they reach every direction, while their i and e effects
/// stay those of the whole firing times cos δ. Why: docs/s3_station_keeping.md,
/// "Momentum dumping". It keeps no state: each orbit's plan follows from that
/// orbit's mean elements alone.
class StationKeepingPlanner {
 public:
  /// @throws std::invalid_argument listing every problem of validate(params).
  explicit StationKeepingPlanner(const StationKeepingParams& params);
  StationKeepingPlan step(const StationKeepingInputs& inputs) const;

 private:
  StationKeepingParams params_;
};

}  // namespace flatsat::station_keeping
