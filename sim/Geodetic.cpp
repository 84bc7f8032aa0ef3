// SPDX-License-Identifier: Apache-2.0
#include "sim/Geodetic.hpp"

#include <algorithm>
#include <cmath>

#include "sim/Constants.hpp"

namespace flatsat::sim {
namespace {

constexpr double kA = kEarthEquatorialRadius_m;
constexpr double kB = kA * (1.0 - kEarthFlattening);                                  // [m] polar radius
constexpr double kE2 = kEarthFlattening * (2.0 - kEarthFlattening);                   // first eccentricity²
constexpr double kEp2 = kE2 / ((1.0 - kEarthFlattening) * (1.0 - kEarthFlattening));  // second e′²

// The NED axes of latitude φ (geodetic or geocentric) and longitude λ as columns in E.
Eigen::Matrix3d nedToEarthFixed(double latitude_rad, double longitude_rad) {
  const double sp = std::sin(latitude_rad);
  const double cp = std::cos(latitude_rad);
  const double sl = std::sin(longitude_rad);
  const double cl = std::cos(longitude_rad);
  Eigen::Matrix3d R;
  R << -sp * cl, -sl, -cp * cl,  //
      -sp * sl, cl, -cp * sl,    //
      cp, 0.0, -sp;
  return R;
}

}  // namespace

Eigen::Vector3d earthFixedFromGeodetic(const GeodeticPosition& p) {
  const double sp = std::sin(p.latitude_rad);
  const double cp = std::cos(p.latitude_rad);
  const double n = kA / std::sqrt(1.0 - kE2 * sp * sp);
  return Eigen::Vector3d((n + p.height_m) * cp * std::cos(p.longitude_rad),
                         (n + p.height_m) * cp * std::sin(p.longitude_rad), (n * (1.0 - kE2) + p.height_m) * sp);
}

GeodeticPosition geodeticFromEarthFixed(const Eigen::Vector3d& r_E_m) {
  // Heikkinen's closed form, step by step as in Zhu (1994).
  const double x = r_E_m.x();
  const double y = r_E_m.y();
  const double z = r_E_m.z();
  const double p = std::hypot(x, y);
  const double f = 54.0 * kB * kB * z * z;
  const double g = p * p + (1.0 - kE2) * z * z - kE2 * (kA * kA - kB * kB);
  const double c = kE2 * kE2 * f * p * p / (g * g * g);
  const double s = std::cbrt(1.0 + c + std::sqrt(c * c + 2.0 * c));
  const double k = s + 1.0 + 1.0 / s;
  const double pp = f / (3.0 * k * k * g * g);
  const double q = std::sqrt(1.0 + 2.0 * kE2 * kE2 * pp);
  // On the polar axis the two terms under the root cancel to r0 = 0; rounding may
  // leave them a hair below zero.
  const double r0 = -pp * kE2 * p / (1.0 + q) +
                    std::sqrt(std::max(0.0, 0.5 * kA * kA * (1.0 + 1.0 / q) -
                                                pp * (1.0 - kE2) * z * z / (q * (1.0 + q)) - 0.5 * pp * p * p));
  const double u = std::hypot(p - kE2 * r0, z);
  const double v = std::sqrt((p - kE2 * r0) * (p - kE2 * r0) + (1.0 - kE2) * z * z);
  const double z0 = kB * kB * z / (kA * v);
  return GeodeticPosition{std::atan2(z + kEp2 * z0, p), p > 0.0 ? std::atan2(y, x) : 0.0,
                          u * (1.0 - kB * kB / (kA * v))};
}

GeocentricPosition geocentricFromGeodetic(const GeodeticPosition& p) {
  const Eigen::Vector3d r_E = earthFixedFromGeodetic(p);
  return GeocentricPosition{r_E.norm(), std::atan2(r_E.z(), r_E.head<2>().norm()), p.longitude_rad};
}

GeocentricPosition geocentricFromEarthFixed(const Eigen::Vector3d& r_E_m) {
  const double p = std::hypot(r_E_m.x(), r_E_m.y());
  return GeocentricPosition{r_E_m.norm(), std::atan2(r_E_m.z(), p), p > 0.0 ? std::atan2(r_E_m.y(), r_E_m.x()) : 0.0};
}

Eigen::Matrix3d R_EG(const GeodeticPosition& p) { return nedToEarthFixed(p.latitude_rad, p.longitude_rad); }

Eigen::Matrix3d R_EC(const GeocentricPosition& p) { return nedToEarthFixed(p.latitude_rad, p.longitude_rad); }

Eigen::Matrix3d R_GC(double geodetic_latitude_rad, double geocentric_latitude_rad) {
  const double d = geocentric_latitude_rad - geodetic_latitude_rad;
  const double c = std::cos(d);
  const double s = std::sin(d);
  Eigen::Matrix3d R;
  R << c, 0.0, -s,    //
      0.0, 1.0, 0.0,  //
      s, 0.0, c;
  return R;
}

}  // namespace flatsat::sim
