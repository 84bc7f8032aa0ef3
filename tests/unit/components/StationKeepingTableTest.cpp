// SPDX-License-Identifier: Apache-2.0
// Seed S3 (Hughes, JP3299143): the six gimballed ion thrusters and the
// firing table. References: the seed's Table I and its statements on the ΔV
// components, and the Sun's geometry (eclipse seasons, the Earth's shadow)
// from the rig's own ephemeris and shadow model.
#include <cmath>
#include <numbers>
#include <set>
#include <tuple>

#include <catch2/catch.hpp>

#include "components/station_keeping/FiringTable.hpp"
#include "components/station_keeping/GeoThrusters.hpp"
#include "sim/Constants.hpp"
#include "sim/SunEphemeris.hpp"
#include "sim/Time.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat;
using namespace flatsat::station_keeping;
using Catch::Matchers::WithinAbs;

namespace {

constexpr double kGeoRadius_m = 42164.17e3;  // (μ / ω_E²)^(1/3): one sidereal day
constexpr std::array<PairFailure, 4> kStates{PairFailure::kNone, PairFailure::k22_28, PairFailure::k20_30,
                                             PairFailure::k24_26};

using Row = std::tuple<int, int, Job>;  // thruster, RA [deg], job

std::multiset<Row> rows(const std::vector<Firing>& firings) {
  std::multiset<Row> out;
  for (const auto& f : firings) {
    out.insert({static_cast<int>(f.thruster), static_cast<int>(std::lround(f.ra_rad / kDeg)) % 360, f.job});
  }
  return out;
}

}  // namespace

TEST_CASE("S3 thrusters: thrust lines through the CM give the seed's ΔV components, pairs share a power unit",
          "[station_keeping][s3]") {
  const GeoThrusterParams p{36.0 * kDeg, 10.0 * kDeg};
  REQUIRE(validate(p).empty());
  CHECK(validate(GeoThrusterParams{0.0, 0.1}).front().rfind("cant_rad:", 0) == 0);
  CHECK(validate(GeoThrusterParams{0.6, -0.1}).front().rfind("slew_rad:", 0) == 0);
  const auto f = [&](GeoThruster t) { return forceDirection_orbital(t, p); };
  for (const auto t : kGeoThrusters) {
    CAPTURE(nameOf(t));
    CHECK_THAT(f(t).norm(), WithinAbs(1.0, 1e-15));
    CHECK(f(t).z() < 0.0);  // the radial part is toward the Earth (seed [0011])
    // The angle to the north–south axis is the cant θ.
    CHECK_THAT(std::acos(std::abs(f(t).y())), WithinAbs(36.0 * kDeg, 1e-12));
    CHECK(partnerOf(partnerOf(t)) == t);
    CHECK(failureOf(t) == failureOf(partnerOf(t)));
    CHECK_FALSE(available(t, failureOf(t)));
    CHECK(available(t, PairFailure::kNone));
  }
  CHECK(partnerOf(GeoThruster::kNW) == GeoThruster::kSE);
  CHECK(partnerOf(GeoThruster::kNC) == GeoThruster::kSC);
  CHECK(partnerOf(GeoThruster::kNE) == GeoThruster::kSW);
  // North row pushes south, south row north.
  CHECK(f(GeoThruster::kNW).y() < 0.0);
  CHECK(f(GeoThruster::kSC).y() > 0.0);
  // Centre thrusters: normal and radial only (seed [0011]).
  CHECK(f(GeoThruster::kNC).x() == 0.0);
  CHECK(f(GeoThruster::kSC).x() == 0.0);
  // Outer four: all three, the tangential part sin θ sin α.
  CHECK_THAT(std::abs(f(GeoThruster::kNE).x()), WithinAbs(std::sin(36.0 * kDeg) * std::sin(10.0 * kDeg), 1e-15));
  // Equal firings of a north pair cancel tangentially (nominal i firing at 90°).
  CHECK_THAT((f(GeoThruster::kNW) + f(GeoThruster::kNE)).x(), WithinAbs(0.0, 1e-15));
  // The diagonal pairs left after a failure cancel the normal and tangential
  // parts and add the radial ones (seed [0008]).
  for (const auto& [a, b] : {std::pair{GeoThruster::kNE, GeoThruster::kSW}, std::pair{GeoThruster::kNW, GeoThruster::kSE}}) {
    const Eigen::Vector3d sum = f(a) + f(b);
    CHECK_THAT(sum.x(), WithinAbs(0.0, 1e-15));
    CHECK_THAT(sum.y(), WithinAbs(0.0, 1e-15));
    CHECK_THAT(sum.z(), WithinAbs(-2.0 * std::sin(36.0 * kDeg) * std::cos(10.0 * kDeg), 1e-15));
  }
}

TEST_CASE("S3 firing table: each state and season gives the seed's Table I rows, with working thrusters only",
          "[station_keeping][s3]") {
  const auto ide = Job::kInclinationDriftEccentricity, md = Job::kMomentumDump, imd = Job::kInclinationAndDump,
             de = Job::kDriftAndEccentricity;
  Season winter;  // winter/spring, no eclipse
  Season summer;
  summer.winter_spring = false;
  Season spring_eclipse;
  spring_eclipse.eclipse = Season::Eclipse::kSpring;
  Season autumn_eclipse;
  autumn_eclipse.winter_spring = false;
  autumn_eclipse.eclipse = Season::Eclipse::kAutumn;
  const double sun_ra = 40.0 * kDeg;  // "RA_sun + 180°" -> 220°

  // Table I, transcribed from the seed ([0034]); the i/MD rows of the centre
  // pair kept in the eclipse seasons as FiringTable.hpp explains.
  for (const auto& season : {winter, summer, spring_eclipse, autumn_eclipse}) {
    CHECK(rows(firingsFor(PairFailure::kNone, season, sun_ra)) ==
          std::multiset<Row>{{20, 90, ide}, {24, 90, ide}, {26, 270, ide}, {30, 270, ide}, {22, 90, md}, {28, 270, md}});
  }
  CHECK(rows(firingsFor(PairFailure::k22_28, winter, sun_ra)) ==
        std::multiset<Row>{{24, 90, imd}, {26, 270, imd}, {24, 0, de}, {26, 0, de}});
  CHECK(rows(firingsFor(PairFailure::k22_28, summer, sun_ra)) ==
        std::multiset<Row>{{20, 90, imd}, {30, 270, imd}, {20, 180, de}, {30, 180, de}});
  CHECK(rows(firingsFor(PairFailure::k20_30, winter, sun_ra)) ==
        std::multiset<Row>{{22, 90, imd}, {28, 270, imd}, {24, 220, de}, {26, 220, de}});
  CHECK(rows(firingsFor(PairFailure::k20_30, spring_eclipse, sun_ra)) ==
        std::multiset<Row>{{22, 90, imd}, {28, 270, imd}, {24, 90, de}, {26, 270, de}});
  CHECK(rows(firingsFor(PairFailure::k20_30, autumn_eclipse, sun_ra)) ==
        std::multiset<Row>{{22, 90, imd}, {28, 270, imd}, {24, 270, de}, {26, 90, de}});
  CHECK(rows(firingsFor(PairFailure::k24_26, summer, sun_ra)) ==
        std::multiset<Row>{{22, 90, imd}, {28, 270, imd}, {20, 220, de}, {30, 220, de}});
  CHECK(rows(firingsFor(PairFailure::k24_26, spring_eclipse, sun_ra)) ==
        std::multiset<Row>{{22, 90, imd}, {28, 270, imd}, {20, 270, de}, {30, 90, de}});
  CHECK(rows(firingsFor(PairFailure::k24_26, autumn_eclipse, sun_ra)) ==
        std::multiset<Row>{{22, 90, imd}, {28, 270, imd}, {20, 90, de}, {30, 270, de}});

  for (const auto state : kStates) {
    for (const auto& season : {winter, summer, spring_eclipse, autumn_eclipse}) {
      for (const auto& firing : firingsFor(state, season, sun_ra)) {
        CAPTURE(nameOf(state), nameOf(firing.thruster));
        CHECK(available(firing.thruster, state));
        CHECK(firing.ra_rad >= 0.0);
        CHECK(firing.ra_rad < 2.0 * std::numbers::pi);
      }
    }
  }
}

TEST_CASE("S3 over a year: two eclipse seasons of about 45 days at the equinoxes, and no firing in the shadow",
          "[station_keeping][s3]") {
  int spring_days = 0, autumn_days = 0, winter_spring_days = 0;
  for (int day = 0; day < 365; ++day) {
    for (const double hour : {0.0, 12.0}) {
      const double jd = sim::julianDate({2027, 1, 1, 0, 0, 0.0}) + day + hour / 24.0;
      const Eigen::Vector3d sun_N_m = sim::sunPosition_N_m(jd);
      const Season season = seasonOf(sun_N_m.normalized(), kGeoRadius_m);
      const double sun_ra = std::atan2(sun_N_m.y(), sun_N_m.x());
      if (hour == 0.0) {
        spring_days += season.eclipse == Season::Eclipse::kSpring;
        autumn_days += season.eclipse == Season::Eclipse::kAutumn;
        winter_spring_days += season.winter_spring;
      }
      for (const auto state : kStates) {
        for (const auto& firing : firingsFor(state, season, sun_ra)) {
          const Eigen::Vector3d r_N_m = kGeoRadius_m * Eigen::Vector3d(std::cos(firing.ra_rad), std::sin(firing.ra_rad), 0.0);
          CAPTURE(day, nameOf(state), nameOf(firing.thruster), firing.ra_rad / kDeg);
          CHECK(sim::illumination(r_N_m, sun_N_m) == 1.0);
        }
      }
    }
  }
  // The Sun's declination below 9.0°: 22..23 days either side of each equinox.
  CHECK(spring_days >= 43);
  CHECK(spring_days <= 47);
  CHECK(autumn_days >= 43);
  CHECK(autumn_days <= 47);
  // December to June solstice: about half the year.
  CHECK(std::abs(winter_spring_days - 182) <= 2);
  // Without the eclipse rows, the d/e firing at RA_sun + 180° would be in the
  // shadow at the equinox: the rows are needed.
  const double equinox = sim::julianDate({2027, 3, 20, 12, 0, 0.0});
  const Eigen::Vector3d sun_N_m = sim::sunPosition_N_m(equinox);
  const Eigen::Vector3d anti_sun_m = -kGeoRadius_m * Eigen::Vector3d(sun_N_m.x(), sun_N_m.y(), 0.0).normalized();
  CHECK(sim::illumination(anti_sun_m, sun_N_m) == 0.0);
}
