// SPDX-License-Identifier: Apache-2.0
// Seed S3's plant: a geostationary orbit left alone for a year under the
// perturbations that matter there, against the published natural drifts
// (Soop, Handbook of Geostationary Orbits, 1994, ch. 3–4): the Sun and Moon
// turn the inclination vector by 0.75–0.95°/yr towards right ascension ~90°,
// and solar pressure drives the eccentricity vector round a yearly circle of
// radius r_e = 3 P C_R (A/m) / (2 n_sun V).
#include <cmath>
#include <numbers>

#include <catch2/catch.hpp>

#include "components/station_keeping/GeoElements.hpp"
#include "sim/Constants.hpp"
#include "sim/OrbitForces.hpp"
#include "sim/OrbitPropagator.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat;
using namespace flatsat::station_keeping;

namespace {

constexpr double kYear_s = 365.25 * 86400.0;

sim::OrbitForceParams geoForces() {
  sim::OrbitForceParams f;
  f.j2 = f.j3 = f.j4 = f.j22 = false;
  f.drag = f.solar_pressure = f.sun_gravity = f.moon_gravity = false;
  f.mass_kg = 2000.0;
  f.srp_area_m2 = 40.0;  // A/m = 0.02 m²/kg: a GEO communications satellite with its arrays
  f.reflectivity_coefficient = 1.3;
  return f;
}

sim::OrbitPropagator::State geostationary() {
  const double r = std::cbrt(sim::kMuEarth_m3_s2 / std::pow(sim::kEarthRotationRate_rad_s, 2));
  return {{r, 0.0, 0.0}, {0.0, std::sqrt(sim::kMuEarth_m3_s2 / r), 0.0}};
}

}  // namespace

TEST_CASE("S3 plant: a year of free drift turns the inclination vector as the Sun and Moon do", "[station_keeping][s3]") {
  auto f = geoForces();
  f.j2 = f.sun_gravity = f.moon_gravity = true;
  sim::OrbitPropagator orbit(f, {2027, 1, 1, 0, 0, 0.0}, geostationary());
  Eigen::Vector2d i_end;
  for (int step = 0; step < static_cast<int>(kYear_s / 600.0); ++step) orbit.step(600.0);
  i_end = synchronousElements(orbit.state().r_N_m, orbit.state().v_N_m_s, 0.0).i;
  const double rate_deg_yr = i_end.norm() / kDeg / (orbit.time_s() / kYear_s);
  const double direction_deg = std::atan2(-i_end.y(), i_end.x()) / kDeg;  // i (sin Ω, −cos Ω): Ω − 90°
  CAPTURE(rate_deg_yr, direction_deg);
  CHECK(rate_deg_yr >= 0.75);
  CHECK(rate_deg_yr <= 0.95);
  CHECK(std::abs(direction_deg) < 20.0);  // the node near RA 90°
}

TEST_CASE("S3 plant: a year of solar pressure drives the eccentricity round the published circle", "[station_keeping][s3]") {
  auto f = geoForces();
  f.solar_pressure = true;
  sim::OrbitPropagator orbit(f, {2027, 1, 1, 0, 0, 0.0}, geostationary());
  const double v = orbit.state().v_N_m_s.norm();
  const double n_sun = 2.0 * std::numbers::pi / kYear_s;
  const double force = sim::kSolarPressure1Au_N_m2 * f.reflectivity_coefficient * f.srp_area_m2 / f.mass_kg;
  const double radius = 3.0 * force / (2.0 * n_sun * v);
  double farthest = 0.0;
  for (int day = 1; day <= 365; ++day) {
    for (int step = 0; step < 144; ++step) orbit.step(600.0);
    farthest = std::max(farthest, synchronousElements(orbit.state().r_N_m, orbit.state().v_N_m_s, 0.0).e.norm());
  }
  const Eigen::Vector2d e_end = synchronousElements(orbit.state().r_N_m, orbit.state().v_N_m_s, 0.0).e;
  CAPTURE(radius, farthest, e_end.norm());
  // From e = 0 on the circle, the farthest point is its diameter across; a year
  // later it is back near the start (the eclipses break the circle slightly).
  CHECK_THAT(farthest, Catch::Matchers::WithinRel(2.0 * radius, 0.05));
  CHECK(e_end.norm() < 0.15 * radius);
  CHECK_THAT(radius, Catch::Matchers::WithinRel(0.011 * 1.3 * 0.02, 0.05));  // Soop's r_e ≈ 0.011 C_R A/m
}
