// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <Eigen/Core>

namespace flatsat::sim {

/// [m] Moon position from the Earth's centre, mean equator and equinox of date (the
/// inertial frame N, as sunPosition_N_m). Low-precision series of the Astronomical
/// Almanac, Vallado Alg. 31 (MOON): about 0.3° in longitude, 0.2° in latitude.
/// @param jd_tt [d] Julian date, terrestrial time (TDB, which the series asks for,
///        differs from TT by less than 2 ms).
Eigen::Vector3d moonPosition_N_m(double jd_tt);

}  // namespace flatsat::sim
