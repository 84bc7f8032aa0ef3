// SPDX-License-Identifier: Apache-2.0
// Seed S3: the synchronous elements station keeping holds, against the
// classical elements a two-body state was made from, and the linear effect of
// an impulse against the exact two-body elements after it.
#include <cmath>
#include <numbers>
#include <random>

#include <catch2/catch.hpp>

#include "components/station_keeping/GeoElements.hpp"
#include "components/station_keeping/GeoThrusters.hpp"
#include "sim/Constants.hpp"
#include "sim/KeplerOrbit.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat;
using namespace flatsat::station_keeping;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

const double kSyncRadius_m = std::cbrt(sim::kMuEarth_m3_s2 / std::pow(sim::kEarthRotationRate_rad_s, 2));

double wrapPi(double a) { return std::remainder(a, 2.0 * std::numbers::pi); }

}  // namespace

TEST_CASE("S3 synchronous elements equal the classical ones the state was made from", "[station_keeping][s3]") {
  struct Case {
    double da_m, e, i_deg, raan_deg, argp_deg, m_deg;
  };
  for (const Case c : {Case{2000.0, 3e-4, 0.07, 80.0, 30.0, 100.0}, Case{-500.0, 1e-5, 0.001, 250.0, 300.0, 10.0},
                       Case{0.0, 0.02, 30.0, 120.0, 200.0, 300.0}}) {
    CAPTURE(c.da_m, c.e, c.i_deg);
    sim::OrbitElements k;
    k.semi_major_axis_m = kSyncRadius_m + c.da_m;
    k.eccentricity = c.e;
    k.inclination_rad = c.i_deg * kDeg;
    k.raan_rad = c.raan_deg * kDeg;
    k.arg_perigee_rad = c.argp_deg * kDeg;
    k.mean_anomaly_rad = c.m_deg * kDeg;
    const auto state = sim::KeplerOrbit(k).at(0.0);
    const double gmst = 1.234;
    const SynchronousElements s = synchronousElements(state.r_N_m, state.v_N_m_s, gmst);
    CHECK_THAT(s.semi_major_axis_m, WithinRel(k.semi_major_axis_m, 1e-12));
    CHECK_THAT(s.drift_rad_s, WithinAbs(std::sqrt(sim::kMuEarth_m3_s2 / std::pow(k.semi_major_axis_m, 3)) -
                                            sim::kEarthRotationRate_rad_s, 1e-17));
    CHECK_THAT(s.i.x(), WithinAbs(k.inclination_rad * std::sin(k.raan_rad), 1e-13));
    CHECK_THAT(s.i.y(), WithinAbs(-k.inclination_rad * std::cos(k.raan_rad), 1e-13));
    const double perigee = k.raan_rad + k.arg_perigee_rad;
    CHECK_THAT(s.e.x(), WithinAbs(c.e * std::cos(perigee), 1e-12));
    CHECK_THAT(s.e.y(), WithinAbs(c.e * std::sin(perigee), 1e-12));
    CHECK_THAT(wrapPi(s.longitude_rad - (perigee + k.mean_anomaly_rad - gmst)), WithinAbs(0.0, 1e-10));
  }
  // Exactly circular and equatorial: no singularity.
  const double v = std::sqrt(sim::kMuEarth_m3_s2 / kSyncRadius_m);
  const SynchronousElements s =
      synchronousElements({0.0, kSyncRadius_m, 0.0}, {-v, 0.0, 0.0}, 0.5);
  CHECK(s.i.norm() == 0.0);
  CHECK(s.e.norm() < 1e-15);
  CHECK_THAT(s.longitude_rad, WithinAbs(std::numbers::pi / 2 - 0.5, 1e-14));
  CHECK_THAT(s.drift_rad_s, WithinAbs(0.0, 1e-16));
}

TEST_CASE("S3 impulse effects: the linear changes of i, e and drift match the exact two-body elements", "[station_keeping][s3]") {
  sim::OrbitElements k;
  k.semi_major_axis_m = kSyncRadius_m + 300.0;
  k.eccentricity = 1e-4;
  k.inclination_rad = 0.02 * kDeg;
  k.raan_rad = 70.0 * kDeg;
  k.arg_perigee_rad = 15.0 * kDeg;
  const sim::KeplerOrbit orbit(k);
  const double v = std::sqrt(sim::kMuEarth_m3_s2 / kSyncRadius_m), n = sim::kEarthRotationRate_rad_s;
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 40; ++trial) {
    const auto state = orbit.at(trial * 2000.0);  // around the orbit
    const Eigen::Vector3d dv_orbital = 0.5 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const Eigen::Vector3d dv_N = R_N_orbital(state.r_N_m, state.v_N_m_s) * dv_orbital;
    const auto before = synchronousElements(state.r_N_m, state.v_N_m_s, 0.0);
    const auto after = synchronousElements(state.r_N_m, state.v_N_m_s + dv_N, 0.0);
    const double ra = std::atan2(state.r_N_m.y(), state.r_N_m.x());
    const ImpulseEffect linear = impulseEffect(dv_orbital, ra, v, n);
    CAPTURE(trial, ra / kDeg, dv_orbital.transpose());
    const double scale = 0.5 / v;  // [rad] the size of each first-order change
    CHECK((after.i - before.i - linear.i).norm() < 2e-3 * scale);
    CHECK((after.e - before.e - linear.e).norm() < 2e-3 * scale);
    CHECK_THAT(after.drift_rad_s - before.drift_rad_s, WithinAbs(linear.drift_rad_s, 2e-3 * 3.0 * n * scale));
    CHECK_THAT(std::remainder(after.longitude_rad - before.longitude_rad, 2.0 * std::numbers::pi),
               WithinAbs(linear.longitude_rad, 2e-3 * 2.0 * scale));
  }
  // The seed's nominal inclination firing: the north row at RA 90° pushes the
  // inclination vector along −x, the south row at 270° the same way.
  const GeoThrusterParams p{36.0 * kDeg, 10.0 * kDeg};
  const auto north_row = impulseEffect(forceDirection_orbital(GeoThruster::kNW, p), 90.0 * kDeg, v, n);
  const auto south_row = impulseEffect(forceDirection_orbital(GeoThruster::kSW, p), 270.0 * kDeg, v, n);
  CHECK(north_row.i.x() < 0.0);
  CHECK_THAT(south_row.i.x(), WithinAbs(north_row.i.x(), 1e-18));
}
