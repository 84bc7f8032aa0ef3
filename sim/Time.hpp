// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace flatsat::sim {

using SimTime = std::int64_t;  // [ns] since scenario epoch

inline constexpr double kSecondsPerDay = 86400.0;
/// [d] Julian date of the J2000.0 epoch, 2000-01-01 12:00 TT.
inline constexpr double kJulianDateJ2000 = 2451545.0;
/// [d] days per Julian century.
inline constexpr double kDaysPerJulianCentury = 36525.0;
/// [s] TT − UTC = 32.184 s + 37 leap seconds (valid since 2017-01-01).
inline constexpr double kTtMinusUtc_s = 69.184;

/// [s] from [ns].
constexpr double toSeconds(SimTime t) { return static_cast<double>(t) * 1e-9; }

/// [ns] from [s], rounded to the nearest nanosecond (halves away from zero).
constexpr SimTime fromSeconds(double t_s) {
  const double ns = t_s * 1e9;
  return static_cast<SimTime>(ns >= 0.0 ? ns + 0.5 : ns - 0.5);
}

/// Calendar date and time of day in UTC (proleptic Gregorian, no leap second).
struct UtcEpoch {
  int year = 2000;      // [-] 1583 (first full Gregorian year) and later
  int month = 1;        // [-] 1..12
  int day = 1;          // [-] 1..days in month
  int hour = 0;         // [h] 0..23
  int minute = 0;       // [min] 0..59
  double second = 0.0;  // [s] [0, 60)

  /// Every out-of-range field as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// Parses "YYYY-MM-DDTHH:MM:SS[.fff…]Z".
/// @throws std::invalid_argument naming the input and what is wrong with it.
UtcEpoch parseIso8601Utc(const std::string& text);

/// Gregorian: every fourth year, but not centuries other than every fourth.
bool isLeapYear(int year);

/// [d] Julian date of a calendar epoch (Meeus, Astronomical Algorithms, Eq. 7.1;
/// Vallado Alg. 14 gives the same for 1900–2100).
double julianDate(const UtcEpoch& epoch);

/// [yr] Year plus the elapsed fraction of that calendar year, e.g. 2025.5 ≈ 2 July 2025.
double decimalYear(const UtcEpoch& epoch);

/// [rad] Greenwich mean sidereal time in [0, 2π), IAU-82 (Vallado Eq. 3-47).
double gmst_rad(double jd_ut1);

/// Rotation from the inertial frame N to the Earth-fixed frame E: v_E = R_EN * v_N.
/// Rotation about z by GMST only (no precession, nutation, polar motion).
Eigen::Matrix3d R_EN(double jd_ut1);

}  // namespace flatsat::sim
