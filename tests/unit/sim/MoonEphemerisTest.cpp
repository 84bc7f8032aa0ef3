// SPDX-License-Identifier: Apache-2.0
#include <cmath>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/MoonEphemeris.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

namespace {

// Mean-of-date equatorial vector of ecliptic longitude λ, latitude β, distance d, with
// the IAU 1976 mean obliquity (Lieske et al. 1977), written out here on its own.
Eigen::Vector3d fromEcliptic(double lambda_deg, double beta_deg, double distance_m, double jd_tt) {
  const double t = (jd_tt - 2451545.0) / 36525.0;
  const double eps = (84381.448 - 46.8150 * t) / 3600.0 * kDeg;
  const double l = lambda_deg * kDeg;
  const double b = beta_deg * kDeg;
  const Eigen::Vector3d ecliptic(std::cos(b) * std::cos(l), std::cos(b) * std::sin(l), std::sin(b));
  const Eigen::Vector3d equatorial(ecliptic.x(), std::cos(eps) * ecliptic.y() - std::sin(eps) * ecliptic.z(),
                                   std::sin(eps) * ecliptic.y() + std::cos(eps) * ecliptic.z());
  return distance_m * equatorial;
}

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) / kDeg;
}

}  // namespace

TEST_CASE("moonPosition_N_m reproduces Vallado Example 5-3", "[sim][moon][orbit]") {
  GIVEN("28 April 1994, 0h (JD 2449470.5, the time argument of the example)") {
    const Eigen::Vector3d r = moonPosition_N_m(2449470.5);
    const Eigen::Vector3d expected(-134240.626e3, -311571.590e3, -126693.785e3);
    THEN("the position matches the book's printed metres within 2 m (the model itself is ~0.3° ≈ 2000 km)") {
      CHECK((r - expected).norm() < 2.0);
    }
  }
}

TEST_CASE("moonPosition_N_m agrees with Meeus' full lunar theory to its stated accuracy", "[sim][moon][orbit]") {
  GIVEN("Meeus, Astronomical Algorithms, Example 47.a: 1992 April 12, 0h TD (JD 2448724.5)") {
    // Geometric, mean equinox of date: λ = 133.162655°, β = −3.229126°, Δ = 368409.7 km.
    const double jd = 2448724.5;
    const Eigen::Vector3d expected = fromEcliptic(133.162655, -3.229126, 368409.7e3, jd);
    const Eigen::Vector3d r = moonPosition_N_m(jd);
    THEN("the direction is within the 0.3° of the low-precision series") { CHECK(angleDeg(r, expected) < 0.3); }
    THEN("the distance is within 0.5 % (parallax series truncated at 0.003°, ≈ 0.3 %)") {
      CHECK(r.norm() == Approx(expected.norm()).epsilon(5e-3));
    }
  }
}

TEST_CASE("moonPosition_N_m follows the lunar orbit over a month", "[sim][moon][orbit]") {
  const double jd0 = 2461041.5;  // 2026-01-01 0h TT
  double min_distance = 1e12;
  double max_distance = 0.0;
  for (double day = 0.0; day < 30.0; day += 0.05) {
    const double d = moonPosition_N_m(jd0 + day).norm();
    min_distance = std::min(min_distance, d);
    max_distance = std::max(max_distance, d);
  }
  THEN("perigee and apogee fall inside the extreme range 356 400–406 700 km") {
    CHECK(min_distance > 356.0e6);
    CHECK(min_distance < 370.0e6);
    CHECK(max_distance < 406.8e6);
    CHECK(max_distance > 400.0e6);
  }
  THEN("the Moon stays within its orbit's 5.1° (+ 0.3° perturbations) of the ecliptic") {
    for (double day = 0.0; day < 30.0; day += 0.25) {
      const double t = (jd0 + day - 2451545.0) / 36525.0;
      const double eps = (84381.448 - 46.8150 * t) / 3600.0 * kDeg;
      const Eigen::Vector3d pole(0.0, -std::sin(eps), std::cos(eps));
      CHECK(std::abs(std::asin(moonPosition_N_m(jd0 + day).normalized().dot(pole))) < 5.45 * kDeg);
    }
  }
}
