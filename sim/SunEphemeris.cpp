// SPDX-License-Identifier: Apache-2.0
#include "sim/SunEphemeris.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/Attitude.hpp"
#include "sim/Constants.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

}  // namespace

Eigen::Vector3d sunPosition_N_m(double jd_tt) {
  // Vallado Alg. 29 (4th ed.); angles in degrees, distance in AU.
  const double t = (jd_tt - kJulianDateJ2000) / kDaysPerJulianCentury;
  const double mean_longitude_deg = 280.460 + 36000.771 * t;
  const double mean_anomaly = (357.5291092 + 35999.05034 * t) * kDegToRad;
  const double ecliptic_longitude =
      (mean_longitude_deg + 1.914666471 * std::sin(mean_anomaly) + 0.019994643 * std::sin(2.0 * mean_anomaly)) *
      kDegToRad;
  const double obliquity = (23.439291 - 0.0130042 * t) * kDegToRad;
  const double distance_au =
      1.000140612 - 0.016708617 * std::cos(mean_anomaly) - 0.000139589 * std::cos(2.0 * mean_anomaly);
  // The ecliptic latitude of the Sun is taken as zero.
  return distance_au * kAstronomicalUnit_m *
         Eigen::Vector3d(std::cos(ecliptic_longitude), std::cos(obliquity) * std::sin(ecliptic_longitude),
                         std::sin(obliquity) * std::sin(ecliptic_longitude));
}

double illumination(const Eigen::Vector3d& r_sat_N_m, const Eigen::Vector3d& r_sun_N_m) {
  // Montenbruck & Gill, Satellite Orbits, §3.4.2, Eq. 3.79–3.87: the Sun and the
  // Earth seen from the satellite as disks of apparent radii a and b, centres c apart.
  const Eigen::Vector3d to_sun = r_sun_N_m - r_sat_N_m;
  const double a = std::asin(kSunRadius_m / to_sun.norm());
  const double b = std::asin(std::min(1.0, kEarthEquatorialRadius_m / r_sat_N_m.norm()));
  const double c = angleBetween(-r_sat_N_m, to_sun);

  if (c >= a + b) return 1.0;                      // disks apart
  if (c <= b - a) return 0.0;                      // Sun behind the Earth: umbra
  if (c <= a - b) return 1.0 - (b * b) / (a * a);  // Earth inside the Sun's disk: annular
  // Partial overlap: area of the lens between two circles (M&G Eq. 3.86–3.87).
  const double x = (c * c + a * a - b * b) / (2.0 * c);
  const double y = std::sqrt(std::max(0.0, a * a - x * x));
  const double occulted =
      a * a * std::acos(std::clamp(x / a, -1.0, 1.0)) + b * b * std::acos(std::clamp((c - x) / b, -1.0, 1.0)) - c * y;
  return 1.0 - occulted / (std::numbers::pi * a * a);
}

}  // namespace flatsat::sim
