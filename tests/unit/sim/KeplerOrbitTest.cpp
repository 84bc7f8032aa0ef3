// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/KeplerOrbit.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

namespace {

OrbitElements moderatelyEccentric() {
  return OrbitElements{8000e3, 0.1, 51.6 * kDeg, 30.0 * kDeg, 45.0 * kDeg, 10.0 * kDeg};
}

}  // namespace

TEST_CASE("solveKepler solves Kepler's equation", "[sim][orbit]") {
  GIVEN("Vallado Example 2-1: M = 235.4°, e = 0.4") {
    THEN("E = 220.512074767522°") {
      CHECK(solveKepler(235.4 * kDeg, 0.4) / kDeg == Approx(220.512074767522).margin(1e-9));
    }
  }
  GIVEN("a circular orbit") {
    THEN("E = M") { CHECK(solveKepler(1.234, 0.0) == 1.234); }
  }
  GIVEN("eccentricities up to 0.99 and several revolutions of M") {
    THEN("E − e sin E = M to near machine precision") {
      for (const double e : {0.0, 0.01, 0.3, 0.7, 0.9, 0.99}) {
        for (double m = -20.0; m <= 20.0; m += 0.173) {
          const double E = solveKepler(m, e);
          CHECK(std::abs(E - e * std::sin(E) - m) < 1e-13);
        }
      }
    }
  }
}

TEST_CASE("OrbitElements::validate lists every violation", "[sim][orbit]") {
  CHECK(moderatelyEccentric().validate().empty());

  OrbitElements bad = moderatelyEccentric();
  bad.semi_major_axis_m = 6000e3;
  bad.eccentricity = 1.2;
  bad.inclination_rad = 4.0;
  bad.raan_rad = std::nan("");
  const auto errors = bad.validate();
  CHECK(errors.size() == 4);
  CHECK(anyStartsWith(errors, "semi_major_axis_m: "));
  CHECK(anyStartsWith(errors, "eccentricity: 1.2 must be in [0, 1)"));
  CHECK(anyStartsWith(errors, "inclination_rad: "));
  CHECK(anyStartsWith(errors, "raan_rad: "));

  OrbitElements grazing = moderatelyEccentric();
  grazing.semi_major_axis_m = 7000e3;
  grazing.eccentricity = 0.2;  // perigee 5600 km
  CHECK(anyStartsWith(grazing.validate(), "eccentricity: perigee"));

  OrbitElements negative = moderatelyEccentric();
  negative.eccentricity = -0.01;
  CHECK(anyStartsWith(negative.validate(), "eccentricity: "));
}

TEST_CASE("KeplerOrbit follows two-body motion", "[sim][orbit]") {
  const OrbitElements el = moderatelyEccentric();
  const KeplerOrbit orbit(el);
  const double a = el.semi_major_axis_m;
  const double e = el.eccentricity;
  const double period = 2.0 * kPi * std::sqrt(a * a * a / kMuEarth_m3_s2);

  THEN("period and mean motion follow Kepler's third law") {
    CHECK(orbit.period_s() == Approx(period).epsilon(1e-14));
    CHECK(orbit.meanMotion_rad_s() == Approx(2.0 * kPi / period).epsilon(1e-14));
  }

  THEN("vis-viva energy and the angular momentum vector are constant") {
    const double energy = -kMuEarth_m3_s2 / (2.0 * a);
    // h = √(μ a (1 − e²)) along the orbit normal (sin Ω sin i, −cos Ω sin i, cos i).
    const Eigen::Vector3d h_expected =
        std::sqrt(kMuEarth_m3_s2 * a * (1.0 - e * e)) *
        Eigen::Vector3d(std::sin(el.raan_rad) * std::sin(el.inclination_rad),
                        -std::cos(el.raan_rad) * std::sin(el.inclination_rad), std::cos(el.inclination_rad));
    for (double t = 0.0; t < 2.0 * period; t += period / 97.0) {
      const KeplerOrbit::State s = orbit.at(t);
      CHECK(0.5 * s.v_N_m_s.squaredNorm() - kMuEarth_m3_s2 / s.r_N_m.norm() == Approx(energy).epsilon(1e-12));
      CHECK((s.r_N_m.cross(s.v_N_m_s) - h_expected).norm() < 1e-12 * h_expected.norm());
    }
  }

  THEN("the velocity is the time derivative of the position") {
    const double dt = 1e-2;
    for (double t = 100.0; t < period; t += period / 7.0) {
      const Eigen::Vector3d numeric = (orbit.at(t + dt).r_N_m - orbit.at(t - dt).r_N_m) / (2.0 * dt);
      CHECK((numeric - orbit.at(t).v_N_m_s).norm() < 1e-6 * orbit.at(t).v_N_m_s.norm());
    }
  }

  THEN("the motion repeats after one period") {
    CHECK((orbit.at(period).r_N_m - orbit.at(0.0).r_N_m).norm() < 1e-5);
    CHECK((orbit.at(3.0 * period + 10.0).v_N_m_s - orbit.at(10.0).v_N_m_s).norm() < 1e-8);
  }
}

TEST_CASE("KeplerOrbit perigee and apogee", "[sim][orbit]") {
  OrbitElements el = moderatelyEccentric();
  el.mean_anomaly_rad = 0.0;
  const KeplerOrbit orbit(el);
  const double a = el.semi_major_axis_m;
  const double e = el.eccentricity;
  const double mu = kMuEarth_m3_s2;

  WHEN("at perigee (t = 0)") {
    const KeplerOrbit::State s = orbit.at(0.0);
    THEN("r = a(1 − e), v = √(μ/a · (1+e)/(1−e)), along the perigee vector P") {
      CHECK(s.r_N_m.norm() == Approx(a * (1.0 - e)).epsilon(1e-14));
      CHECK(s.v_N_m_s.norm() == Approx(std::sqrt(mu / a * (1.0 + e) / (1.0 - e))).epsilon(1e-14));
      const double cO = std::cos(el.raan_rad), sO = std::sin(el.raan_rad);
      const double cw = std::cos(el.arg_perigee_rad), sw = std::sin(el.arg_perigee_rad);
      const double ci = std::cos(el.inclination_rad), si = std::sin(el.inclination_rad);
      const Eigen::Vector3d P(cO * cw - sO * sw * ci, sO * cw + cO * sw * ci, sw * si);
      CHECK((s.r_N_m.normalized() - P).norm() < 1e-14);
      CHECK(std::abs(s.r_N_m.dot(s.v_N_m_s)) < 1e-6 * s.r_N_m.norm() * s.v_N_m_s.norm());
    }
  }
  WHEN("half a period later, at apogee") {
    const KeplerOrbit::State s = orbit.at(0.5 * orbit.period_s());
    THEN("r = a(1 + e), opposite to perigee") {
      CHECK(s.r_N_m.norm() == Approx(a * (1.0 + e)).epsilon(1e-13));
      CHECK(s.r_N_m.normalized().dot(orbit.at(0.0).r_N_m.normalized()) == Approx(-1.0).epsilon(1e-13));
    }
  }
  WHEN("the orbit is equatorial and circular") {
    const KeplerOrbit circle(OrbitElements{7000e3, 0.0, 0.0, 0.0, 0.0, 0.0});
    THEN("it starts on +x moving along +y at the circular speed") {
      const KeplerOrbit::State s = circle.at(0.0);
      CHECK((s.r_N_m - Eigen::Vector3d(7000e3, 0.0, 0.0)).norm() < 1e-6);
      CHECK((s.v_N_m_s - Eigen::Vector3d(0.0, std::sqrt(mu / 7000e3), 0.0)).norm() < 1e-9);
    }
  }
}
