// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <Eigen/Core>

namespace flatsat::sim {

/// [m] Sun position from the Earth's centre, mean equator and equinox of date
/// (used as the inertial frame N; the equinox of date precesses ≈ 0.014°/yr from J2000).
/// Astronomical Almanac low-precision formula, Vallado Alg. 29 (SUN), ~0.01° accurate.
/// @param jd_tt [d] Julian date, terrestrial time.
Eigen::Vector3d sunPosition_N_m(double jd_tt);

/// [-] Visible fraction of the solar disk: 1 full Sun, 0 umbra, in between penumbra
/// (or annular eclipse). Conical shadow of a spherical Earth of equatorial radius.
double illumination(const Eigen::Vector3d& r_sat_N_m, const Eigen::Vector3d& r_sun_N_m);

}  // namespace flatsat::sim
