// SPDX-License-Identifier: Apache-2.0
#include "sim/Time.hpp"

#include <cctype>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sim/Attitude.hpp"
#include "sim/Format.hpp"

namespace flatsat::sim {

bool isLeapYear(int year) { return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0; }

namespace {

int daysInMonth(int year, int month) {
  static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month == 2 && isLeapYear(year) ? 29 : kDays[month - 1];
}

// The layout check has already guaranteed that these characters are digits.
int digitsAt(const std::string& text, std::size_t pos, std::size_t count) { return std::stoi(text.substr(pos, count)); }

[[noreturn]] void rejectTime(const std::string& text, const std::string& reason) {
  throw std::invalid_argument("invalid ISO 8601 UTC time \"" + text + "\": " + reason);
}

}  // namespace

std::vector<std::string> UtcEpoch::validate() const {
  std::vector<std::string> errors;
  if (year < 1583) errors.push_back("year: " + std::to_string(year) + " is before the Gregorian calendar (1583)");
  if (month < 1 || month > 12) {
    errors.push_back("month: " + std::to_string(month) + " not in 1..12");
  } else if (day < 1 || day > daysInMonth(year, month)) {
    errors.push_back("day: " + std::to_string(day) + " not in 1.." + std::to_string(daysInMonth(year, month)) +
                     " for " + std::to_string(year) + "-" + std::to_string(month));
  }
  if (hour < 0 || hour > 23) errors.push_back("hour: " + std::to_string(hour) + " not in 0..23");
  if (minute < 0 || minute > 59) errors.push_back("minute: " + std::to_string(minute) + " not in 0..59");
  if (!(second >= 0.0 && second < 60.0)) {
    errors.push_back("second: " + formatNumber(second) + " not in [0, 60) (leap seconds are not supported)");
  }
  return errors;
}

UtcEpoch parseIso8601Utc(const std::string& text) {
  // Fixed layout YYYY-MM-DDTHH:MM:SS, then an optional fraction, then 'Z'.
  static constexpr char kLayout[] = "dddd-dd-ddTdd:dd:dd";
  for (std::size_t i = 0; i + 1 < sizeof(kLayout); ++i) {
    const bool ok = i < text.size() && (kLayout[i] == 'd' ? std::isdigit(static_cast<unsigned char>(text[i])) != 0
                                                          : text[i] == kLayout[i]);
    if (!ok)
      rejectTime(text,
                 "expected the form YYYY-MM-DDTHH:MM:SS[.fff]Z (mismatch at character " + std::to_string(i + 1) + ")");
  }
  UtcEpoch epoch;
  epoch.year = digitsAt(text, 0, 4);
  epoch.month = digitsAt(text, 5, 2);
  epoch.day = digitsAt(text, 8, 2);
  epoch.hour = digitsAt(text, 11, 2);
  epoch.minute = digitsAt(text, 14, 2);

  std::size_t pos = 19;
  if (pos < text.size() && text[pos] == '.') {
    const std::size_t first = ++pos;
    while (pos < text.size() && std::isdigit(static_cast<unsigned char>(text[pos]))) ++pos;
    if (pos == first) rejectTime(text, "no digits after the decimal point of the seconds");
  }
  if (pos >= text.size() || text[pos] != 'Z') rejectTime(text, "missing the 'Z' (UTC) designator after the seconds");
  if (pos + 1 != text.size()) rejectTime(text, "unexpected characters after 'Z'");
  epoch.second = std::stod(text.substr(17, pos - 17));

  const std::vector<std::string> errors = epoch.validate();
  if (!errors.empty()) {
    std::string reason = errors.front();
    for (std::size_t i = 1; i < errors.size(); ++i) reason += "; " + errors[i];
    rejectTime(text, reason);
  }
  return epoch;
}

double julianDate(const UtcEpoch& epoch) {
  // Meeus Eq. 7.1: January and February count as months 13 and 14 of the
  // previous year so that the leap day falls at the end of the counting year.
  int y = epoch.year;
  int m = epoch.month;
  if (m <= 2) {
    y -= 1;
    m += 12;
  }
  const int a = y / 100;
  const int b = 2 - a + a / 4;
  const double day_fraction = (epoch.hour + (epoch.minute + epoch.second / 60.0) / 60.0) / 24.0;
  return std::floor(365.25 * (y + 4716)) + std::floor(30.6001 * (m + 1)) + epoch.day + b - 1524.5 + day_fraction;
}

double decimalYear(const UtcEpoch& epoch) {
  const double jd_start = julianDate(UtcEpoch{epoch.year, 1, 1, 0, 0, 0.0});
  const double jd_end = julianDate(UtcEpoch{epoch.year + 1, 1, 1, 0, 0, 0.0});
  return epoch.year + (julianDate(epoch) - jd_start) / (jd_end - jd_start);
}

double gmst_rad(double jd_ut1) {
  // Vallado Eq. 3-47 gives GMST in seconds of time; reduce modulo one day
  // before scaling so that the large secular term does not cost precision.
  const double t = (jd_ut1 - kJulianDateJ2000) / kDaysPerJulianCentury;
  const double gmst_s = 67310.54841 + (876600.0 * 3600.0 + 8640184.812866) * t + 0.093104 * t * t - 6.2e-6 * t * t * t;
  double reduced_s = std::fmod(gmst_s, kSecondsPerDay);
  if (reduced_s < 0.0) reduced_s += kSecondsPerDay;
  const double gmst = reduced_s * (2.0 * std::numbers::pi / kSecondsPerDay);
  // Rounding of the scaling can turn the largest reduced value into exactly 2π.
  return gmst < 2.0 * std::numbers::pi ? gmst : 0.0;
}

Eigen::Matrix3d R_EN(double jd_ut1) { return rot3(gmst_rad(jd_ut1)); }

}  // namespace flatsat::sim
