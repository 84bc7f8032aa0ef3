// SPDX-License-Identifier: Apache-2.0
#pragma once

// SGP4's canonical units and the mean elements shared by the near-Earth and
// deep-space parts of the model. SGP4 works in Earth radii and minutes (and
// returns km, km/s); these units stay inside the SGP4 files.

namespace flatsat::sim {

/// WGS-72 constants of SGP4 (Vallado, Crawford, Hujsak & Kelso 2006, AIAA 2006-6753: the
/// 'wgs72' set of its reference code's getgravconst). Element sets are fitted with these
/// values, so they must not be replaced by WGS-84 ones.
namespace sgp4_wgs72 {
inline constexpr double kMu_km3_s2 = 398600.8;  // [km^3/s^2] Earth gravitational parameter
inline constexpr double kRadius_km = 6378.135;  // [km] equatorial radius, SGP4's length unit
inline constexpr double kJ2 = 0.001082616;      // [-] zonal harmonics (un-normalised)
inline constexpr double kJ3 = -0.00000253881;   // [-]
inline constexpr double kJ4 = -0.00000165597;   // [-]
inline constexpr double kJ3OverJ2 = kJ3 / kJ2;  // [-]
/// [1/min] sqrt(mu / R^3) in Earth radii per minute: 60 / sqrt(R^3 / mu) as Vallado
/// computes it, written out because std::sqrt is not constexpr; these 16 digits
/// round-trip to exactly that double (checked in Sgp4Test).
inline constexpr double kXke = 0.07436691613317342;
}  // namespace sgp4_wgs72

/// Mean elements of SGP4 at one time, in its units.
struct Sgp4MeanElements {
  double ecc = 0.0;           // [-] eccentricity
  double incl = 0.0;          // [rad] inclination
  double node = 0.0;          // [rad] right ascension of the ascending node
  double argp = 0.0;          // [rad] argument of perigee
  double mean_anomaly = 0.0;  // [rad]
  double mean_motion = 0.0;   // [rad/min]
};

}  // namespace flatsat::sim
