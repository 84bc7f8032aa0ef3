// SPDX-License-Identifier: Apache-2.0
#include "sim/Frames.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "sim/Time.hpp"

namespace flatsat::sim {
namespace {

constexpr double kArcsecToRad = std::numbers::pi / (180.0 * 3600.0);

}  // namespace

double earthRotationAngle_rad(double jd_ut1) {
  // IERS 2010 Eq. 5.15 with the whole days split off: θ/2π = frac(Tu) +
  // 0.7790572732640 + 0.00273781191135448 Tu keeps full precision for any date.
  const double tu = jd_ut1 - kJulianDateJ2000;
  const double turns = std::fmod(tu, 1.0) + 0.7790572732640 + 0.00273781191135448 * tu;
  double fraction = std::fmod(turns, 1.0);
  if (fraction < 0.0) fraction += 1.0;
  const double theta = 2.0 * std::numbers::pi * fraction;
  // Rounding of the scaling can turn the largest fraction into exactly 2π.
  return theta < 2.0 * std::numbers::pi ? theta : 0.0;
}

double meanObliquity_rad(double jd_tt) {
  const double t = (jd_tt - kJulianDateJ2000) / kDaysPerJulianCentury;
  return (84381.448 + t * (-46.8150 + t * (-0.00059 + t * 0.001813))) * kArcsecToRad;
}

Eigen::Matrix3d R_N_RSW(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s) {
  const Eigen::Vector3d radial = r_N_m.normalized();
  const Eigen::Vector3d normal = r_N_m.cross(v_N_m_s).normalized();
  Eigen::Matrix3d r;
  r.col(0) = radial;
  r.col(1) = normal.cross(radial);
  r.col(2) = normal;
  return r;
}

Eigen::Matrix3d R_N_EastNorthZenith(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s) {
  const Eigen::Matrix3d rsw = R_N_RSW(r_N_m, v_N_m_s);
  Eigen::Matrix3d r;
  r << rsw.col(1), rsw.col(2), rsw.col(0);
  return r;
}

Eigen::Matrix3d R_N_LVLH(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s) {
  const Eigen::Vector3d nadir = -r_N_m.normalized();
  const Eigen::Vector3d negative_normal = -r_N_m.cross(v_N_m_s).normalized();
  Eigen::Matrix3d r;
  r.col(0) = negative_normal.cross(nadir);
  r.col(1) = negative_normal;
  r.col(2) = nadir;
  return r;
}

Eigen::Matrix3d R_N_S2Orbital(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s) {
  return R_N_LVLH(r_N_m, v_N_m_s) * Eigen::Vector3d(-1.0, 1.0, -1.0).asDiagonal();
}

Eigen::Matrix3d R_N_SunEcliptic(const Eigen::Vector3d& sun_N_unit, double jd_tt) {
  // North pole of the ecliptic in the equatorial frame: the z axis turned by ε about x.
  const double obliquity = meanObliquity_rad(jd_tt);
  const Eigen::Vector3d pole_N(0.0, -std::sin(obliquity), std::cos(obliquity));
  const Eigen::Vector3d x = sun_N_unit.normalized();
  // pole × X is perpendicular to the pole, i.e. parallel to the ecliptic, and to X.
  const Eigen::Vector3d y = pole_N.cross(x).normalized();
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = y;
  r.col(2) = x.cross(y);
  return r;
}

}  // namespace flatsat::sim
