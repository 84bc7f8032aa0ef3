// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <Eigen/Dense>

namespace flatsat::station_keeping {

/// The synchronous elements of a geostationary orbit (Soop, Handbook of
/// Geostationary Orbits, 1994, ch. 3), non-singular at zero inclination
/// and eccentricity: what station keeping holds.
struct SynchronousElements {
  double longitude_rad = 0.0;  ///< [rad] mean longitude east of Greenwich, (−π, π]
  double drift_rad_s = 0.0;    ///< [rad/s] mean motion minus the Earth's rotation: the longitude drift
  Eigen::Vector2d e{0.0, 0.0};  ///< [-] eccentricity vector e (cos ϖ, sin ϖ), ϖ = Ω + ω
  Eigen::Vector2d i{0.0, 0.0};  ///< [rad] inclination vector i (sin Ω, −cos Ω)
  double semi_major_axis_m = 0.0;  ///< [m]
};

/// The osculating synchronous elements of the state (r, v) in the inertial
/// frame N (equator and equinox of date), with Greenwich at sidereal angle
/// `gmst_rad`. Exact two-body relations: the eccentricity vector and the mean
/// longitude are taken in the equinoctial frame (Broucke & Cefola, "On the
/// equinoctial orbit elements", Celest. Mech. 5, 1972), so they hold at any
/// inclination below 90°.
SynchronousElements synchronousElements(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s, double gmst_rad);

/// The first-order change of the synchronous elements by an impulse ΔV in
/// the local orbital frame of GeoThrusters.hpp (x east = tangential T,
/// y north = normal N, z zenith = radial R) given at right ascension s on a
/// geostationary orbit of speed `v_m_s` and mean motion `n_rad_s`: Gauss's
/// variational equations linearised about the circular equatorial orbit
/// (Soop 1994, ch. 5):
///   Δi = ΔV_N / v (sin s, −cos s)
///   Δe = ΔV_R / v (sin s, −cos s) + 2 ΔV_T / v (cos s, sin s)
///   Δdrift = −3 n ΔV_T / v
///   Δl = −2 ΔV_R / v (the mean longitude jumps at a radial impulse).
struct ImpulseEffect {
  double drift_rad_s = 0.0;
  double longitude_rad = 0.0;
  Eigen::Vector2d e{0.0, 0.0};
  Eigen::Vector2d i{0.0, 0.0};
};
ImpulseEffect impulseEffect(const Eigen::Vector3d& dv_orbital_m_s, double ra_rad, double v_m_s, double n_rad_s);

}  // namespace flatsat::station_keeping
