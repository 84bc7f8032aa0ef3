// SPDX-License-Identifier: Apache-2.0
#include <cmath>

#include <catch2/catch.hpp>

#include "sim/Constants.hpp"
#include "sim/SunEphemeris.hpp"
#include "sim/Time.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

namespace {

constexpr double kTtMinusUtc_d = 69.184 / 86400.0;

double declination_deg(const Eigen::Vector3d& r) { return std::asin(r.z() / r.norm()) / kDeg; }

// Visible fraction of a disk of radius a whose centre is c from the centre of an
// occulting disk of radius b, by counting grid points (independent of the
// closed-form lens area).
double visibleFractionByGrid(double a, double b, double c) {
  constexpr int kN = 1500;
  int inside_sun = 0;
  int visible = 0;
  for (int i = 0; i < kN; ++i) {
    for (int j = 0; j < kN; ++j) {
      const double x = -a + 2.0 * a * (i + 0.5) / kN;
      const double y = -a + 2.0 * a * (j + 0.5) / kN;
      if (x * x + y * y > a * a) continue;
      ++inside_sun;
      if ((x + c) * (x + c) + y * y > b * b) ++visible;
    }
  }
  return static_cast<double>(visible) / inside_sun;
}

}  // namespace

TEST_CASE("sunPosition_N_m reproduces Vallado Example 5-1", "[sim][sun]") {
  GIVEN("2 April 2006, 00:00 UTC (JD 2453827.5)") {
    const Eigen::Vector3d r = sunPosition_N_m(2453827.5);
    const Eigen::Vector3d expected(146186212e3, 28788976e3, 12481064e3);
    THEN("the position matches within 0.01 % of its length") { CHECK((r - expected).norm() < 1e-4 * expected.norm()); }
  }
}

TEST_CASE("sunPosition_N_m agrees with the seasons", "[sim][sun]") {
  // Equinox and solstice instants from the Astronomical Almanac (USNO), in UTC.
  const double tt = kTtMinusUtc_d;
  GIVEN("the March equinox, 2026-03-20 14:46 UTC") {
    const Eigen::Vector3d r = sunPosition_N_m(julianDate(UtcEpoch{2026, 3, 20, 14, 46, 0.0}) + tt);
    THEN("the Sun is on the equator towards the equinox (+x)") {
      CHECK(std::abs(declination_deg(r)) < 0.02);
      CHECK(r.normalized().x() > std::cos(0.02 * kDeg));
    }
  }
  GIVEN("the June solstice, 2025-06-21 02:42 UTC") {
    const Eigen::Vector3d r = sunPosition_N_m(julianDate(UtcEpoch{2025, 6, 21, 2, 42, 0.0}) + tt);
    THEN("the declination equals the obliquity, 23.436°") { CHECK(declination_deg(r) == Approx(23.436).margin(0.02)); }
  }
  GIVEN("perihelion (early January) and aphelion (early July)") {
    const double r_peri = sunPosition_N_m(julianDate(UtcEpoch{2026, 1, 3, 17, 0, 0.0}) + tt).norm();
    const double r_aph = sunPosition_N_m(julianDate(UtcEpoch{2026, 7, 6, 17, 0, 0.0}) + tt).norm();
    THEN("the distances are a(1 ∓ e) with e = 0.0167") {
      CHECK(r_peri / kAstronomicalUnit_m == Approx(1.0 - 0.0167).margin(2e-4));
      CHECK(r_aph / kAstronomicalUnit_m == Approx(1.0 + 0.0167).margin(2e-4));
    }
  }
}

TEST_CASE("illumination models umbra and penumbra", "[sim][sun]") {
  const Eigen::Vector3d r_sun = kAstronomicalUnit_m * Eigen::Vector3d::UnitX();
  const double R = kEarthEquatorialRadius_m;

  WHEN("the satellite is on the Sun side") { CHECK(illumination(Eigen::Vector3d(7000e3, 0.0, 0.0), r_sun) == 1.0); }
  WHEN("the satellite is over the terminator, outside the shadow cylinder") {
    CHECK(illumination(Eigen::Vector3d(0.0, 7000e3, 0.0), r_sun) == 1.0);
  }
  WHEN("the satellite is close behind the Earth") {
    CHECK(illumination(Eigen::Vector3d(-7000e3, 0.0, 0.0), r_sun) == 0.0);
    CHECK(illumination(Eigen::Vector3d(-7000e3, 0.5 * R, 0.0), r_sun) == 0.0);
  }
  WHEN("the satellite grazes the shadow edge") {
    const Eigen::Vector3d r_sat(-3000e3, R, 0.0);
    const double nu = illumination(r_sat, r_sun);
    THEN("it is in the penumbra and sees the lens-shaped remainder of the disk") {
      CHECK(nu > 0.0);
      CHECK(nu < 1.0);
      const Eigen::Vector3d to_sun = r_sun - r_sat;
      const double a = std::asin(kSunRadius_m / to_sun.norm());
      const double b = std::asin(R / r_sat.norm());
      const double c = std::acos((-r_sat).normalized().dot(to_sun.normalized()));
      CHECK(nu == Approx(visibleFractionByGrid(a, b, c)).margin(2e-3));
    }
  }
  WHEN("the satellite crosses the shadow boundary") {
    THEN("illumination rises monotonically from 0 to 1") {
      double previous = -1.0;
      for (double y = R - 40e3; y <= R + 40e3; y += 1e3) {
        const double nu = illumination(Eigen::Vector3d(-3000e3, y, 0.0), r_sun);
        CHECK(nu >= previous);
        previous = nu;
      }
      CHECK(illumination(Eigen::Vector3d(-3000e3, R - 40e3, 0.0), r_sun) == 0.0);
      CHECK(previous == 1.0);
    }
  }
  WHEN("the satellite is beyond the tip of the umbra cone, on the axis") {
    const Eigen::Vector3d r_sat(-2.0e9, 0.0, 0.0);
    const double a = std::asin(kSunRadius_m / (kAstronomicalUnit_m + 2.0e9));
    const double b = std::asin(R / 2.0e9);
    THEN("the Earth covers the centre of the disk: an annular eclipse, 1 − b²/a²") {
      CHECK(illumination(r_sat, r_sun) == Approx(1.0 - b * b / (a * a)).epsilon(1e-12));
    }
  }
}
