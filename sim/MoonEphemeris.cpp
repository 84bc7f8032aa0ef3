// SPDX-License-Identifier: Apache-2.0
#include "sim/MoonEphemeris.hpp"

#include <cmath>
#include <numbers>

#include "sim/Constants.hpp"
#include "sim/Frames.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

double sinDeg(double deg) { return std::sin(deg * kDegToRad); }
double cosDeg(double deg) { return std::cos(deg * kDegToRad); }

}  // namespace

Eigen::Vector3d moonPosition_N_m(double jd_tt) {
  // Vallado Alg. 31 (4th ed.); arguments in degrees. The same four arguments
  // drive the longitude and the parallax terms.
  const double t = (jd_tt - kJulianDateJ2000) / kDaysPerJulianCentury;
  const double arg1 = 134.9 + 477198.85 * t;
  const double arg2 = 259.2 - 413335.38 * t;
  const double arg3 = 235.7 + 890534.23 * t;
  const double arg4 = 269.9 + 954397.70 * t;
  const double longitude =
      (218.32 + 481267.8813 * t + 6.29 * sinDeg(arg1) - 1.27 * sinDeg(arg2) + 0.66 * sinDeg(arg3) +
       0.21 * sinDeg(arg4) - 0.19 * sinDeg(357.5 + 35999.05 * t) - 0.11 * sinDeg(186.6 + 966404.05 * t)) *
      kDegToRad;
  const double latitude = (5.13 * sinDeg(93.3 + 483202.03 * t) + 0.28 * sinDeg(228.2 + 960400.87 * t) -
                           0.28 * sinDeg(318.3 + 6003.18 * t) - 0.17 * sinDeg(217.6 - 407332.20 * t)) *
                          kDegToRad;
  // Horizontal parallax: the Earth's equatorial radius seen from the Moon.
  const double parallax =
      (0.9508 + 0.0518 * cosDeg(arg1) + 0.0095 * cosDeg(arg2) + 0.0078 * cosDeg(arg3) + 0.0028 * cosDeg(arg4)) *
      kDegToRad;
  const double distance_m = kEarthEquatorialRadius_m / std::sin(parallax);

  // Ecliptic of date → mean equator of date: rotation about x by −ε.
  const double obliquity = meanObliquity_rad(jd_tt);
  const double ce = std::cos(obliquity);
  const double se = std::sin(obliquity);
  const double cb = std::cos(latitude);
  const double sb = std::sin(latitude);
  const double cl = std::cos(longitude);
  const double sl = std::sin(longitude);
  return distance_m * Eigen::Vector3d(cb * cl, ce * cb * sl - se * sb, se * cb * sl + ce * sb);
}

}  // namespace flatsat::sim
