// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/LU>
#include <catch2/catch.hpp>

#include "sim/Time.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;
using Catch::Matchers::Contains;

TEST_CASE("SimTime converts between nanoseconds and seconds", "[sim][time]") {
  static_assert(fromSeconds(2.0) == 2'000'000'000);
  static_assert(toSeconds(1'500'000'000) == 1.5);
  CHECK(fromSeconds(0.1) == 100'000'000);
  CHECK(fromSeconds(-0.1) == -100'000'000);
  CHECK(fromSeconds(1.0000000006) == 1'000'000'001);  // rounded, not truncated
  CHECK(fromSeconds(1.0000000004) == 1'000'000'000);
  CHECK(fromSeconds(toSeconds(123'456'789'012)) == 123'456'789'012);
}

TEST_CASE("parseIso8601Utc reads valid timestamps", "[sim][time]") {
  GIVEN("a whole-second timestamp") {
    const UtcEpoch e = parseIso8601Utc("2026-03-20T12:00:00Z");
    THEN("every field is read") {
      CHECK(e.year == 2026);
      CHECK(e.month == 3);
      CHECK(e.day == 20);
      CHECK(e.hour == 12);
      CHECK(e.minute == 0);
      CHECK(e.second == 0.0);
    }
  }
  GIVEN("fractional seconds and a leap day") {
    const UtcEpoch e = parseIso8601Utc("2024-02-29T23:59:59.125Z");
    CHECK(e.day == 29);
    CHECK(e.minute == 59);
    CHECK(e.second == 59.125);
  }
}

TEST_CASE("parseIso8601Utc rejects bad input with a reason", "[sim][time]") {
  CHECK_THROWS_AS(parseIso8601Utc("2026-13-01T00:00:00Z"), std::invalid_argument);
  CHECK_THROWS_WITH(parseIso8601Utc("2026-13-01T00:00:00Z"), Contains("month: 13"));
  CHECK_THROWS_WITH(parseIso8601Utc("2026-00-01T00:00:00Z"), Contains("month: 0"));
  CHECK_THROWS_WITH(parseIso8601Utc("2025-02-29T00:00:00Z"), Contains("day: 29 not in 1..28"));
  CHECK_THROWS_WITH(parseIso8601Utc("2026-04-31T00:00:00Z"), Contains("day: 31"));
  CHECK_THROWS_WITH(parseIso8601Utc("2026-03-20T24:00:00Z"), Contains("hour: 24"));
  CHECK_THROWS_WITH(parseIso8601Utc("2026-03-20T12:60:00Z"), Contains("minute: 60"));
  CHECK_THROWS_WITH(parseIso8601Utc("2026-03-20T12:00:60Z"), Contains("leap seconds"));
  CHECK_THROWS_WITH(parseIso8601Utc("2026-03-20 12:00:00Z"), Contains("character 11"));
  CHECK_THROWS_WITH(parseIso8601Utc("2026-03-20T12:00:00"), Contains("'Z'"));
  CHECK_THROWS_WITH(parseIso8601Utc("2026-03-20T12:00:00+01:00"), Contains("'Z'"));
  CHECK_THROWS_WITH(parseIso8601Utc("2026-03-20T12:00:00.Z"), Contains("no digits"));
  CHECK_THROWS_WITH(parseIso8601Utc("2026-03-20T12:00:00Zjunk"), Contains("after 'Z'"));
  CHECK_THROWS_WITH(parseIso8601Utc("1500-01-01T00:00:00Z"), Contains("Gregorian"));
  CHECK_THROWS_WITH(parseIso8601Utc(""), Contains("YYYY-MM-DD"));
}

TEST_CASE("julianDate matches published values", "[sim][time]") {
  // J2000.0 epoch.
  CHECK(julianDate(UtcEpoch{2000, 1, 1, 12, 0, 0.0}) == 2451545.0);
  // Meeus, Astronomical Algorithms, Example 7.a (1957 Oct 4.81) and Table 7.a.
  CHECK(julianDate(UtcEpoch{1957, 10, 4, 19, 26, 24.0}) == Approx(2436116.31).margin(1e-8));
  CHECK(julianDate(UtcEpoch{1988, 1, 27, 0, 0, 0.0}) == 2447187.5);
  CHECK(julianDate(UtcEpoch{1600, 1, 1, 0, 0, 0.0}) == 2305447.5);
  // Vallado, Fundamentals of Astrodynamics, Example 3-4 (1996 Oct 26 14:20 UT1).
  CHECK(julianDate(UtcEpoch{1996, 10, 26, 14, 20, 0.0}) == Approx(2450383.09722222).margin(1e-8));
}

TEST_CASE("decimalYear counts the fraction of the calendar year", "[sim][time]") {
  CHECK(decimalYear(UtcEpoch{2025, 1, 1, 0, 0, 0.0}) == 2025.0);
  // 1 Jan → 2 Jul 12:00 is 181 + 1 + 0.5 = 182.5 of 365 days.
  CHECK(decimalYear(UtcEpoch{2025, 7, 2, 12, 0, 0.0}) == Approx(2025.5).epsilon(1e-12));
  // Leap year: 365.5 of 366 days.
  CHECK(decimalYear(UtcEpoch{2024, 12, 31, 12, 0, 0.0}) == Approx(2024.0 + 365.5 / 366.0).epsilon(1e-12));
}

TEST_CASE("gmst_rad reproduces Vallado Example 3-5", "[sim][time]") {
  GIVEN("1992 August 20, 12:14 UT1") {
    const double jd = julianDate(UtcEpoch{1992, 8, 20, 12, 14, 0.0});
    THEN("JD and GMST match the published example") {
      CHECK(jd == Approx(2448855.009722).margin(1e-6));
      CHECK(gmst_rad(jd) / kDeg == Approx(152.578787810).margin(1e-6));
    }
  }
  GIVEN("the J2000 epoch") {
    THEN("GMST is the constant term, 67310.54841 s = 280.46061837504°") {
      CHECK(gmst_rad(2451545.0) / kDeg == Approx(67310.54841 / 240.0).margin(1e-9));
    }
  }
  GIVEN("dates over two centuries") {
    THEN("GMST stays in [0, 2π)") {
      for (double jd = 2415020.5; jd < 2488070.5; jd += 123.456) {
        const double g = gmst_rad(jd);
        CHECK(g >= 0.0);
        CHECK(g < 2.0 * std::numbers::pi);
      }
    }
  }
}

TEST_CASE("R_EN rotates the inertial frame into the Earth-fixed frame", "[sim][time]") {
  const double jd = 2460755.0;  // 2025-03-20 12:00 UT1
  const Eigen::Matrix3d R = R_EN(jd);
  const double g = gmst_rad(jd);
  THEN("it is a proper rotation about z") {
    CHECK((R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-15);
    CHECK(R.determinant() == Approx(1.0).margin(1e-15));
    CHECK((R * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm() < 1e-15);
  }
  THEN("the Greenwich meridian, at right ascension GMST, maps to the Earth-fixed x axis") {
    const Eigen::Vector3d greenwich_N(std::cos(g), std::sin(g), 0.0);
    CHECK((R * greenwich_N - Eigen::Vector3d::UnitX()).norm() < 1e-15);
  }
  THEN("an inertially fixed direction drifts west (−y) as the Earth turns east") {
    const Eigen::Vector3d later = R_EN(jd + 60.0 / 86400.0) * (R.transpose() * Eigen::Vector3d::UnitX());
    CHECK(later.y() < 0.0);
    CHECK(std::atan2(-later.y(), later.x()) == Approx(60.0 * 7.2921158553e-5).epsilon(1e-6));
  }
}
