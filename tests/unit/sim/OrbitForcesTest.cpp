// SPDX-License-Identifier: Apache-2.0
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "sim/Constants.hpp"
#include "sim/MoonEphemeris.hpp"
#include "sim/OrbitForces.hpp"
#include "sim/SunEphemeris.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

namespace {

constexpr double kR = 6378136.3;

// Zonal potential −(μ/r) J_n (R/r)ⁿ P_n(z/r) with the Legendre polynomials written out.
double zonalPotential(const Eigen::Vector3d& r, int n, double j_n) {
  const double d = r.norm();
  const double s = r.z() / d;
  const double p = n == 2   ? 0.5 * (3 * s * s - 1)
                   : n == 3 ? 0.5 * (5 * s * s * s - 3 * s)
                            : (35 * std::pow(s, 4) - 30 * s * s + 3) / 8;
  return -kMu / d * j_n * std::pow(kR / d, n) * p;
}

// Central-difference gradient of the zonal potential.
Eigen::Vector3d numericalGradient(const Eigen::Vector3d& r, int n, double j_n) {
  Eigen::Vector3d g;
  const double h = 1.0;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d dr = Eigen::Vector3d::Zero();
    dr(k) = h;
    g(k) = (zonalPotential(r + dr, n, j_n) - zonalPotential(r - dr, n, j_n)) / (2 * h);
  }
  return g;
}

Eigen::Vector3d zonal(const Eigen::Vector3d& r, int n) { return zonalAcceleration_N(r, n == 2, n == 3, n == 4); }

}  // namespace

TEST_CASE("zonal accelerations are the gradients of the zonal potential", "[sim][orbit]") {
  const Eigen::Vector3d points[] = {{7000e3, 0.0, 0.0}, {4000e3, -3000e3, 4500e3}, {-1000e3, 2000e3, -6800e3}};
  GIVEN("J2 in its Cartesian form: a = −(3/2) J2 μ R²/r⁵ (x(1−5z²/r²), y(…), z(3−5z²/r²))") {
    for (const Eigen::Vector3d& r : points) {
      const double d = r.norm();
      const double k = -1.5 * kEgm2008J2 * kMu * kR * kR / std::pow(d, 5);
      const double q = 5.0 * r.z() * r.z() / (d * d);
      const Eigen::Vector3d expected(k * r.x() * (1 - q), k * r.y() * (1 - q), k * r.z() * (3 - q));
      CHECK((zonal(r, 2) - expected).norm() < 1e-12 * expected.norm());
    }
  }
  GIVEN("J2, J3 and J4 against the numerical gradient of the potential") {
    for (const Eigen::Vector3d& r : points) {
      CHECK((zonal(r, 2) - numericalGradient(r, 2, kEgm2008J2)).norm() <
            1e-7 * numericalGradient(r, 2, kEgm2008J2).norm());
      CHECK((zonal(r, 3) - numericalGradient(r, 3, kEgm2008J3)).norm() <
            1e-6 * numericalGradient(r, 3, kEgm2008J3).norm());
      CHECK((zonal(r, 4) - numericalGradient(r, 4, kEgm2008J4)).norm() <
            1e-6 * numericalGradient(r, 4, kEgm2008J4).norm());
    }
  }
  GIVEN("several terms at once") {
    THEN("the result is the sum of the single terms") {
      for (const Eigen::Vector3d& r : points) {
        const Eigen::Vector3d sum = zonal(r, 2) + zonal(r, 3) + zonal(r, 4);
        CHECK((zonalAcceleration_N(r, true, true, true) - sum).norm() < 1e-15 * sum.norm());
        CHECK((zonalAcceleration_N(r, false, true, true) - zonal(r, 3) - zonal(r, 4)).norm() < 1e-18);
        CHECK(zonalAcceleration_N(r, false, false, false).norm() == 0.0);
      }
    }
  }
  GIVEN("a point on the equator") {
    THEN("J2 pulls inward by (3/2) μ J2 R²/r⁴ and J3 (odd) pulls along the axis only") {
      const Eigen::Vector3d r(7000e3, 0.0, 0.0);
      CHECK(zonal(r, 2).x() == Approx(-1.5 * kMu * kEgm2008J2 * kR * kR / std::pow(7000e3, 4)));
      CHECK(zonal(r, 3).head<2>().norm() == 0.0);
      CHECK(zonal(r, 3).z() == Approx(1.5 * kMu * kEgm2008J3 * std::pow(kR, 3) / std::pow(7000e3, 5)));
    }
  }
}

TEST_CASE("the sectoral J22 term: the gradient of its potential, and the drift it gives a geostationary orbit",
          "[sim][orbit]") {
  // V22 = (μ/r)(R/r)² P22(sin φ)(C22 cos 2λ + S22 sin 2λ), P22 = 3 cos² φ, in
  // latitude and longitude of the Earth turned by θ.
  const double theta = 0.7;
  const auto potential = [&](const Eigen::Vector3d& r_N) {
    const double lon = std::atan2(r_N.y(), r_N.x()) - theta, d = r_N.norm();
    const double cos_lat = std::hypot(r_N.x(), r_N.y()) / d;
    return kMu / d * std::pow(kR / d, 2) * 3.0 * cos_lat * cos_lat *
           (kEgm2008C22 * std::cos(2 * lon) + kEgm2008S22 * std::sin(2 * lon));
  };
  for (const Eigen::Vector3d& r : {Eigen::Vector3d(7000e3, 0.0, 0.0), Eigen::Vector3d(4000e3, -3000e3, 4500e3),
                                   Eigen::Vector3d(-30000e3, 25000e3, -2000e3)}) {
    Eigen::Vector3d gradient;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d dr = Eigen::Vector3d::Zero();
      dr(k) = 1.0;
      gradient(k) = (potential(r + dr) - potential(r - dr)) / 2.0;
    }
    CHECK((sectoralJ22Acceleration_N(r, theta) - gradient).norm() < 1e-6 * gradient.norm());
  }
  // On the geostationary ring the along-track part drives the longitude:
  // λ̈ = −3 a_T / r. Published: stable points near 75°E and 105°W, unstable
  // near 15°W and 165°E, and |λ̈| up to about 0.0017°/day² (Soop, Handbook of
  // Geostationary Orbits, 1994, ch. 3).
  const double r_geo = 42164.17e3;
  const double deg_per_day2 = 86400.0 * 86400.0 * 180.0 / std::numbers::pi;
  double largest = 0.0;
  std::vector<double> stable, unstable;
  double previous = 0.0;
  for (int tenth = 0; tenth <= 3600; ++tenth) {
    const double lon = tenth * 0.1 * std::numbers::pi / 180.0, ra = lon + theta;
    const Eigen::Vector3d r(r_geo * std::cos(ra), r_geo * std::sin(ra), 0.0), east(-std::sin(ra), std::cos(ra), 0.0);
    const double lon_accel = -3.0 * sectoralJ22Acceleration_N(r, theta).dot(east) / r_geo * deg_per_day2;
    largest = std::max(largest, std::abs(lon_accel));
    if (tenth > 0 && previous > 0.0 && lon_accel <= 0.0) stable.push_back(tenth * 0.1);  // pushed back from both sides
    if (tenth > 0 && previous < 0.0 && lon_accel >= 0.0) unstable.push_back(tenth * 0.1);
    previous = lon_accel;
  }
  CHECK_THAT(largest, Catch::Matchers::WithinRel(0.0017, 0.03));
  REQUIRE(stable.size() == 2);
  REQUIRE(unstable.size() == 2);
  CHECK_THAT(stable[0], Catch::Matchers::WithinAbs(75.0, 0.5));
  CHECK_THAT(stable[1], Catch::Matchers::WithinAbs(255.0, 0.5));  // 105°W
  CHECK_THAT(unstable[0], Catch::Matchers::WithinAbs(165.0, 0.5));
  CHECK_THAT(unstable[1], Catch::Matchers::WithinAbs(345.0, 0.5));  // 15°W
}

TEST_CASE("drag opposes the velocity relative to the rotating atmosphere", "[sim][orbit]") {
  const double r = 6778137.0;
  const double v = std::sqrt(kMu / r);
  const double rho = 3e-12;
  const double b = 2.2 * 0.03 / 4.0;
  GIVEN("a prograde equatorial orbit") {
    const Eigen::Vector3d a = dragAcceleration_N({r, 0.0, 0.0}, {0.0, v, 0.0}, rho, b);
    THEN("the air moves with the Earth at ωr, so |a| = ½ ρ B (v − ωr)²") {
      const double v_rel = v - 7.292115e-5 * r;
      CHECK(a.y() == Approx(-0.5 * rho * b * v_rel * v_rel).epsilon(1e-12));
      CHECK(a.x() == 0.0);
      CHECK(a.z() == 0.0);
    }
  }
  GIVEN("a polar orbit crossing the equator") {
    const Eigen::Vector3d a = dragAcceleration_N({r, 0.0, 0.0}, {0.0, 0.0, v}, rho, b);
    THEN("the Earth's rotation adds a cross wind: a_y = +½ ρ B |v_rel| ωr") {
      const double w = 7.292115e-5 * r;
      const double speed = std::hypot(v, w);
      CHECK(a.z() == Approx(-0.5 * rho * b * speed * v).epsilon(1e-12));
      CHECK(a.y() == Approx(0.5 * rho * b * speed * w).epsilon(1e-12));
    }
  }
}

TEST_CASE("solar radiation pressure on a cannonball", "[sim][orbit]") {
  const double cr_a_m = 1.3 * 0.03 / 4.0;
  const double pressure = 4.54e-6;  // [N/m²] 1361 W/m² / c, rounded
  const Eigen::Vector3d sun = kAstronomicalUnit_m * Eigen::Vector3d::UnitX();
  GIVEN("the satellite on the Sun side, 1 AU − 7000 km from the Sun") {
    const Eigen::Vector3d a = solarPressureAcceleration_N({7000e3, 0.0, 0.0}, sun, cr_a_m);
    const double scale = std::pow(kAstronomicalUnit_m / (kAstronomicalUnit_m - 7000e3), 2);
    THEN("it is pushed away from the Sun by P C_R A/m (AU/d)²") {
      CHECK(a.x() == Approx(-pressure * cr_a_m * scale).epsilon(2e-3));
      CHECK(a.tail<2>().norm() == 0.0);
    }
  }
  GIVEN("positions all around a low orbit, day and night side") {
    THEN("the pressure is always ν P C_R A/m (AU/d)² with ν = illumination()") {
      for (double u = 0.0; u < 360.0; u += 0.25) {
        const double ur = u * std::numbers::pi / 180.0;
        const Eigen::Vector3d r = 6800e3 * Eigen::Vector3d(std::cos(ur), 0.3 * std::sin(ur), 0.95 * std::sin(ur));
        const double d = (sun - r).norm();
        const double expected =
            illumination(r, sun) * kSolarPressure1Au_N_m2 * cr_a_m * std::pow(kAstronomicalUnit_m / d, 2);
        CHECK(solarPressureAcceleration_N(r, sun, cr_a_m).norm() == Approx(expected).margin(1e-20));
      }
    }
  }
  GIVEN("the satellite in the umbra") {
    THEN("there is no pressure") { CHECK(solarPressureAcceleration_N({-7000e3, 0.0, 0.0}, sun, cr_a_m).norm() == 0.0); }
  }
  GIVEN("the satellite in the penumbra") {
    const Eigen::Vector3d r(-3000e3, kEarthEquatorialRadius_m, 0.0);
    THEN("the pressure is scaled by the visible fraction of the Sun") {
      const double full = solarPressureAcceleration_N(r, sun, cr_a_m).norm() / illumination(r, sun);
      CHECK(illumination(r, sun) > 0.0);
      CHECK(illumination(r, sun) < 1.0);
      CHECK(full == Approx(pressure * cr_a_m).epsilon(3e-3));
    }
  }
}

TEST_CASE("third-body perturbations of the Sun and the Moon", "[sim][orbit]") {
  const double r = 7000e3;
  GIVEN("the Sun 1 AU away along the satellite's radius") {
    const double s = kAstronomicalUnit_m;
    const Eigen::Vector3d a = thirdBodyAcceleration_N({r, 0.0, 0.0}, {s, 0.0, 0.0}, kMuSun_m3_s2);
    THEN("the tide is μ[1/(s−r)² − 1/s²] ≈ 2μr/s³ ≈ 5.5e-7 m/s², outward") {
      const double expected = kMuSun_m3_s2 * (1.0 / ((s - r) * (s - r)) - 1.0 / (s * s));
      CHECK(a.x() == Approx(expected).epsilon(1e-6));
      CHECK(a.x() == Approx(2.0 * kMuSun_m3_s2 * r / (s * s * s)).epsilon(1e-4));
      CHECK(a.x() == Approx(5.5e-7).epsilon(0.02));
    }
  }
  GIVEN("the Sun perpendicular to the satellite's radius") {
    const double s = kAstronomicalUnit_m;
    const Eigen::Vector3d a = thirdBodyAcceleration_N({r, 0.0, 0.0}, {0.0, s, 0.0}, kMuSun_m3_s2);
    THEN("the tide squeezes inward by μr/d³ (d² = r² + s²)") {
      CHECK(a.x() == Approx(-kMuSun_m3_s2 * r / std::pow(std::hypot(r, s), 3)).epsilon(1e-6));
      CHECK(std::abs(a.y()) < 1e-3 * std::abs(a.x()));
    }
  }
  GIVEN("the Moon of the ephemeris, with the satellite on the Earth–Moon line") {
    const Eigen::Vector3d moon = moonPosition_N_m(2461041.5);
    const double d = moon.norm();
    const Eigen::Vector3d a = thirdBodyAcceleration_N(r * moon.normalized(), moon, kMuMoon_m3_s2);
    THEN("the tide is μ_M[1/(d−r)² − 1/d²] ≈ 2μ_M r/d³, towards the Moon, about twice the Sun's") {
      CHECK(a.dot(moon.normalized()) ==
            Approx(kMuMoon_m3_s2 * (1.0 / ((d - r) * (d - r)) - 1.0 / (d * d))).epsilon(1e-6));
      CHECK(a.norm() == Approx(2.0 * kMuMoon_m3_s2 * r / (d * d * d)).epsilon(0.05));
      const double sun_tide = 2.0 * kMuSun_m3_s2 * r / std::pow(kAstronomicalUnit_m, 3);
      CHECK(a.norm() / sun_tide > 1.7);
      CHECK(a.norm() / sun_tide < 2.9);
    }
  }
}

TEST_CASE("OrbitForces sums the switched-on terms", "[sim][orbit]") {
  const Eigen::Vector3d r(4000e3, -3000e3, 4500e3);
  const Eigen::Vector3d v(-3000.0, 4000.0, 3000.0);
  const double jd = 2461041.5;
  Ephemerides bodies{sunPosition_N_m(jd), moonPosition_N_m(jd)};
  const OrbitForceParams params;
  const OrbitForces forces(params);
  const Ephemerides computed = forces.ephemeridesAt(jd);
  CHECK((computed.sun_N_m - bodies.sun_N_m).norm() == 0.0);
  CHECK((computed.moon_N_m - bodies.moon_N_m).norm() == 0.0);

  const Atmosphere atmosphere(params.atmosphere);
  const double rho = atmosphere.density_kg_m3(r, bodies.sun_N_m.normalized());
  const Eigen::Vector3d expected = pointMassAcceleration_N(r, kMuEarth_m3_s2) + zonal(r, 2) + zonal(r, 3) +
                                   zonal(r, 4) + dragAcceleration_N(r, v, rho, 2.2 * 0.03 / 4.0) +
                                   solarPressureAcceleration_N(r, bodies.sun_N_m, 1.3 * 0.03 / 4.0) +
                                   thirdBodyAcceleration_N(r, bodies.sun_N_m, kMuSun_m3_s2) +
                                   thirdBodyAcceleration_N(r, bodies.moon_N_m, kMuMoon_m3_s2);
  CHECK((forces.acceleration_N(r, v, bodies) - expected).norm() < 1e-15 * expected.norm());

  OrbitForceParams only_j2;
  only_j2.central_gravity = only_j2.j3 = only_j2.j4 = false;
  only_j2.drag = only_j2.solar_pressure = only_j2.sun_gravity = only_j2.moon_gravity = false;
  const OrbitForces j2(only_j2);
  CHECK(j2.ephemeridesAt(jd).sun_N_m.norm() == 0.0);
  CHECK(j2.ephemeridesAt(jd).moon_N_m.norm() == 0.0);
  CHECK((j2.acceleration_N(r, v, bodies) - zonal(r, 2)).norm() == 0.0);
}

TEST_CASE("OrbitForceParams::validate lists every violation", "[sim][orbit]") {
  CHECK(OrbitForceParams{}.validate().empty());
  OrbitForceParams bad;
  bad.mass_kg = 0.0;
  bad.drag_area_m2 = -1.0;
  bad.drag_coefficient = std::nan("");
  bad.srp_area_m2 = -0.1;
  bad.reflectivity_coefficient = 2.5;
  bad.tt_minus_utc_s = 0.0;
  bad.atmosphere.bulge_exponent = 1.0;
  const auto errors = bad.validate();
  CHECK(errors.size() == 7);
  for (const char* field : {"mass_kg:", "drag_area_m2:", "drag_coefficient:", "srp_area_m2:",
                            "reflectivity_coefficient:", "tt_minus_utc_s:", "atmosphere.bulge_exponent:"}) {
    CHECK(anyStartsWith(errors, field));
  }
  CHECK_THROWS_AS(OrbitForces{bad}, std::invalid_argument);
}
