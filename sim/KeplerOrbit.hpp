// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/Constants.hpp"

namespace flatsat::sim {

/// Classical orbital elements in the inertial frame N, osculating at t = 0.
struct OrbitElements {
  double semi_major_axis_m = 6938137.0;  // [m] a, perigee above the Earth's equatorial radius
  double eccentricity = 0.0;             // [-] e in [0, 1)
  double inclination_rad = 0.0;          // [rad] i in [0, π]
  double raan_rad = 0.0;                 // [rad] Ω, right ascension of the ascending node
  double arg_perigee_rad = 0.0;          // [rad] ω, argument of perigee
  double mean_anomaly_rad = 0.0;         // [rad] M at t = 0

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// [rad] Eccentric anomaly E with E − e sin E = mean_anomaly (Vallado Alg. 2, KepEqtnE:
/// Newton's method), converged to 1e-14 rad; E keeps M's number of revolutions. e in [0, 1).
double solveKepler(double mean_anomaly, double e);

/// Unperturbed two-body motion.
class KeplerOrbit {
 public:
  struct State {
    Eigen::Vector3d r_N_m;    // [m] position
    Eigen::Vector3d v_N_m_s;  // [m/s] velocity
  };

  /// Elements must be valid (OrbitElements::validate() empty).
  explicit KeplerOrbit(const OrbitElements& elements, double mu = kMuEarth_m3_s2);

  /// State at t_s [s] after the elements' epoch.
  State at(double t_s) const;

  double period_s() const;          // [s]
  double meanMotion_rad_s() const;  // [rad/s]

 private:
  OrbitElements elements_;
  double mu_;
  double mean_motion_rad_s_;
  Eigen::Matrix3d R_NP_;  // perifocal (PQW) to inertial
};

}  // namespace flatsat::sim
