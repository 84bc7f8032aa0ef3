// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <numbers>

namespace flatsat::sim {

/// [rad] half a turn and a whole one.
inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// [m^3/s^2] Earth gravitational parameter (WGS-84, incl. atmosphere).
inline constexpr double kMuEarth_m3_s2 = 3.986004418e14;
/// [m] WGS-84 equatorial radius; also the radius of the spherical Earth in the shadow model.
inline constexpr double kEarthEquatorialRadius_m = 6378137.0;
/// [-] WGS-84 flattening.
inline constexpr double kEarthFlattening = 1.0 / 298.257223563;
/// [rad/s] Earth rotation rate relative to the equinox (IERS conventional value).
inline constexpr double kEarthRotationRate_rad_s = 7.292115e-5;
/// [m] astronomical unit (IAU 2012 Resolution B2, exact).
inline constexpr double kAstronomicalUnit_m = 149597870700.0;
/// [m] nominal solar radius (IAU 2015 Resolution B3).
inline constexpr double kSunRadius_m = 6.957e8;
/// [m] IGRF reference radius a (mean Earth radius used by the Gauss coefficients).
inline constexpr double kIgrfReferenceRadius_m = 6371200.0;

}  // namespace flatsat::sim
