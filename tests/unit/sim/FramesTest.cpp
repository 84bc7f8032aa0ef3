// SPDX-License-Identifier: Apache-2.0
#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <catch2/catch.hpp>

#include "sim/Frames.hpp"
#include "sim/KeplerOrbit.hpp"
#include "sim/SunEphemeris.hpp"
#include "sim/Time.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

namespace {

constexpr double kArcsec = kDeg / 3600.0;

void checkRotation(const Eigen::Matrix3d& r) {
  CHECK((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-12);
  CHECK(r.determinant() == Approx(1.0).epsilon(1e-12));
}

double wrapPi(double angle) { return std::remainder(angle, 2.0 * kPi); }

}  // namespace

TEST_CASE("earthRotationAngle_rad follows IERS 2010 Eq. 5.15", "[sim][frames][orbit]") {
  GIVEN("J2000.0 (JD_UT1 2451545.0)") {
    THEN("θ = 2π · 0.7790572732640 = 280.46061837504°") {
      CHECK(earthRotationAngle_rad(2451545.0) / kDeg == Approx(280.46061837504).margin(1e-9));
    }
  }
  GIVEN("one UT1 day later") {
    THEN("the Earth has turned 360° + 0.98561° (the sidereal excess 0.00273781191135448 turn)") {
      const double d = wrapPi(earthRotationAngle_rad(2460000.5) - earthRotationAngle_rad(2460000.5 - 1.0));
      CHECK(d / kDeg == Approx(0.00273781191135448 * 360.0).margin(1e-8));
    }
  }
  GIVEN("dates from 1990 to 2040") {
    // IERS 2010 Eq. 5.32: GMST = ERA + accumulated precession in right ascension. Time.hpp's
    // GMST is IAU-82, whose implied precession rate (IAU 1976, 4612.43"/cy) exceeds the IAU
    // 2006 one by 0.28"/cy, so the two agree to 0.02" + 0.3"/cy · |T|.
    THEN("GMST − ERA is the precession in right ascension to IAU-82's accuracy") {
      for (int year = 1990; year <= 2040; year += 5) {
        const double jd = julianDate(UtcEpoch{year, 6, 1, 3, 0, 0.0});
        const double t = (jd - 2451545.0) / 36525.0;
        const double precession = (0.014506 + 4612.156534 * t + 1.3915817 * t * t) * kArcsec;
        const double difference = wrapPi(gmst_rad(jd) - earthRotationAngle_rad(jd) - precession);
        CHECK(std::abs(difference) < (0.02 + 0.3 * std::abs(t)) * kArcsec);
      }
    }
  }
  THEN("the angle stays in [0, 2π) for dates before J2000") {
    const double theta = earthRotationAngle_rad(2440000.3);
    CHECK(theta >= 0.0);
    CHECK(theta < 2.0 * kPi);
  }
}

TEST_CASE("meanObliquity_rad matches published values", "[sim][frames][orbit]") {
  CHECK(meanObliquity_rad(2451545.0) / kDeg == Approx(23.4392911).margin(1e-7));
  // Meeus, Astronomical Algorithms, Example 22.a: 1987 April 10, 0h TD: ε0 = 23°26'27.407".
  CHECK(meanObliquity_rad(2446895.5) / kArcsec == Approx(23.0 * 3600.0 + 26.0 * 60.0 + 27.407).margin(2e-3));
}

TEST_CASE("R_N_RSW and R_N_LVLH follow the orbit", "[sim][frames][orbit]") {
  const KeplerOrbit orbit(OrbitElements{7000e3, 0.0, 51.6 * kDeg, 30.0 * kDeg, 0.0, 0.0});
  for (double t = 0.0; t < orbit.period_s(); t += 700.0) {
    const KeplerOrbit::State s = orbit.at(t);
    const Eigen::Vector3d h = s.r_N_m.cross(s.v_N_m_s);
    const Eigen::Matrix3d rsw = R_N_RSW(s.r_N_m, s.v_N_m_s);
    const Eigen::Matrix3d lvlh = R_N_LVLH(s.r_N_m, s.v_N_m_s);
    checkRotation(rsw);
    checkRotation(lvlh);
    // RSW: radial, along-track (= velocity on a circular orbit), orbit normal.
    CHECK((rsw.col(0) - s.r_N_m.normalized()).norm() < 1e-12);
    CHECK((rsw.col(1) - s.v_N_m_s.normalized()).norm() < 1e-12);
    CHECK((rsw.col(2) - h.normalized()).norm() < 1e-12);
    // LVLH: along-track, negative orbit normal, nadir.
    CHECK((lvlh.col(0) - s.v_N_m_s.normalized()).norm() < 1e-12);
    CHECK((lvlh.col(1) + h.normalized()).norm() < 1e-12);
    CHECK((lvlh.col(2) + s.r_N_m.normalized()).norm() < 1e-12);
    // A vector's RSW coordinates: the velocity is (0, v, 0).
    const Eigen::Vector3d v_rsw = rsw.transpose() * s.v_N_m_s;
    CHECK(std::abs(v_rsw.x()) < 1e-9);
    CHECK(v_rsw.y() == Approx(s.v_N_m_s.norm()));
  }
}

TEST_CASE("R_N_SunEcliptic builds the S0 reference frame", "[sim][frames][orbit]") {
  const double jd = 2451545.0;
  const double eps = 23.4392911 * kDeg;
  const Eigen::Vector3d pole(0.0, -std::sin(eps), std::cos(eps));
  GIVEN("the Sun at the March equinox (+x)") {
    const Eigen::Matrix3d r = R_N_SunEcliptic(Eigen::Vector3d::UnitX(), jd);
    THEN("Y is the ecliptic's direction of motion (0, cos ε, sin ε) and Z its north pole") {
      checkRotation(r);
      CHECK((r.col(0) - Eigen::Vector3d::UnitX()).norm() < 1e-15);
      CHECK((r.col(1) - Eigen::Vector3d(0.0, std::cos(eps), std::sin(eps))).norm() < 1e-9);
      CHECK((r.col(2) - pole).norm() < 1e-9);
    }
  }
  GIVEN("the Sun at the June solstice, (0, cos ε, sin ε)") {
    const Eigen::Matrix3d r = R_N_SunEcliptic(Eigen::Vector3d(0.0, std::cos(eps), std::sin(eps)), jd);
    THEN("Y points to −x, the Sun's motion there") {
      CHECK((r.col(1) + Eigen::Vector3d::UnitX()).norm() < 1e-9);
      CHECK((r.col(2) - pole).norm() < 1e-9);
    }
  }
  GIVEN("the Sun of the ephemeris through a year") {
    THEN("X is the Sun and Z the ecliptic pole of date") {
      for (double day = 0.0; day < 365.0; day += 30.0) {
        const double jd_tt = 2461041.5 + day;
        const double t = (jd_tt - 2451545.0) / 36525.0;
        const double eps_t = (84381.448 - 46.8150 * t) * kArcsec;
        const Eigen::Vector3d pole_t(0.0, -std::sin(eps_t), std::cos(eps_t));
        const Eigen::Vector3d sun = sunPosition_N_m(jd_tt).normalized();
        const Eigen::Matrix3d r = R_N_SunEcliptic(sun, jd_tt);
        checkRotation(r);
        CHECK((r.col(0) - sun).norm() < 1e-15);
        CHECK(r.col(2).dot(pole_t) > std::cos(1e-7));
        CHECK(std::abs(r.col(1).dot(pole_t)) < 1e-9);
      }
    }
  }
}
