// SPDX-License-Identifier: Apache-2.0
// Seed S3 closed over a year, algorithms only: the GEO plant (J2–J4, J22,
// Sun, Moon, solar pressure with the Earth's shadow) under the mean-element
// filter and the planner, each firing given as an impulse at its right
// ascension. What is asked of the station box: longitude within
// ±0.05°, inclination within 0.05°, eccentricity below 2e-4, in every state;
// and no firing in the Earth's shadow. At 75°E (next to the stable point of
// the J22 field) and at 105°E every state holds the box. At 19.2°E, where J22
// pulls east at 0.0016°/day², the nominal and 22/28 states hold it; with the
// 20/30 or 24/26 pair failed the one diagonal pair left for the drift must give
// about 1.6 m/s a year more east than west, and each of its firings turns e as
// much as its drift is worth, so the longitude there reaches 0.053° and 0.080°
// (docs/s3_station_keeping.md).
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>

#include <catch2/catch.hpp>

#include "components/station_keeping/MeanElements.hpp"
#include "components/station_keeping/StationKeepingPlanner.hpp"
#include "sim/Constants.hpp"
#include "sim/OrbitForces.hpp"
#include "sim/OrbitPropagator.hpp"
#include "sim/SunEphemeris.hpp"
#include "sim/Time.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat;
using namespace flatsat::station_keeping;

namespace {

constexpr double kYear_s = 365.25 * 86400.0;
constexpr double kStep_s = 600.0;
const sim::UtcEpoch kEpoch{2027, 1, 1, 0, 0, 0.0};

struct YearResult {
  double longitude_dev_deg_max = 0.0;
  double inclination_deg_max = 0.0;
  double eccentricity_max = 0.0;  // of the daily means
  double dv_m_s = 0.0;
  std::map<int, int> firings;  // per thruster
  int in_shadow = 0;
};

/// [m] The radius where the J2-strengthened gravity turns with the Earth.
double synchronousRadius() {
  const double w2 = std::pow(sim::kEarthRotationRate_rad_s, 2), R = sim::kEgm2008Radius_m;
  double r = std::cbrt(sim::kMuEarth_m3_s2 / w2);
  for (int k = 0; k < 20; ++k) r = std::cbrt(sim::kMuEarth_m3_s2 * (1.0 + 1.5 * sim::kEgm2008J2 * R * R / (r * r)) / w2);
  return r;
}

YearResult flyYear(PairFailure failure, double station_rad, bool centre_pair_equal = false) {
  sim::OrbitForceParams f;
  f.j22 = true;
  f.drag = false;
  f.mass_kg = 2000.0;
  f.srp_area_m2 = 40.0;
  f.reflectivity_coefficient = 1.3;
  const double jd0 = sim::julianDate(kEpoch);
  const double r = synchronousRadius(), ra0 = station_rad + sim::gmst_rad(jd0);
  const Eigen::Vector3d east0(-std::sin(ra0), std::cos(ra0), 0.0);
  sim::OrbitPropagator orbit(f, kEpoch,
                             {r * Eigen::Vector3d(std::cos(ra0), std::sin(ra0), 0.0), sim::kEarthRotationRate_rad_s * r * east0});
  StationKeepingParams params;
  params.station_longitude_rad = station_rad;
  params.mass_kg = f.mass_kg;
  params.centre_pair_equal = centre_pair_equal;
  const StationKeepingPlanner planner(params);
  MeanElementsFilter filter({});
  std::vector<PlannedFiring> pending;
  YearResult result;

  const auto fire = [&](const PlannedFiring& firing) {
    const auto& s = orbit.state();
    const Eigen::Vector3d d = firing.dv_m_s * forceDirection_orbital(firing.thruster, params.thrusters);
    const Eigen::Vector3d dv_N = R_N_orbital(s.r_N_m, s.v_N_m_s) * d;
    const Eigen::Vector3d sun = sim::sunPosition_N_m(jd0 + orbit.time_s() / 86400.0);
    result.in_shadow += sim::illumination(s.r_N_m, sun) < 1.0;
    result.dv_m_s += firing.dv_m_s;
    filter.impulse(impulseEffect(d, std::atan2(s.r_N_m.y(), s.r_N_m.x()), s.v_N_m_s.norm(), sim::kEarthRotationRate_rad_s),
                   orbit.time_s());
    ++result.firings[static_cast<int>(firing.thruster)];
    orbit.restart(orbit.time_s(), {s.r_N_m, s.v_N_m_s + dv_N});
  };

  // Seconds until the spacecraft reaches the firing's right ascension, 0 once
  // it is there or just past it: a step aimed at it lands within a few
  // millidegrees either side (the rate of right ascension is ω only on average).
  const auto secondsTo = [&](const PlannedFiring& firing) {
    const auto& s = orbit.state();
    const double angle = std::remainder(firing.ra_rad - std::atan2(s.r_N_m.y(), s.r_N_m.x()), 2 * std::numbers::pi);
    if (angle < 1e-6 && angle > -0.01) return 0.0;
    return (angle < 0.0 ? angle + 2 * std::numbers::pi : angle) / sim::kEarthRotationRate_rad_s;
  };
  while (orbit.time_s() < kYear_s) {
    // Firings due now go first: a new plan must not drop them.
    const auto due = std::find_if(pending.begin(), pending.end(), [&](const auto& f) { return secondsTo(f) == 0.0; });
    if (due != pending.end()) {
      fire(*due);
      pending.erase(due);
      continue;
    }
    const double t = orbit.time_s(), jd = jd0 + t / 86400.0;
    const auto& s = orbit.state();
    const SynchronousElements osc = synchronousElements(s.r_N_m, s.v_N_m_s, sim::gmst_rad(jd));
    const Eigen::Vector3d r_E = sim::R_EN(jd) * s.r_N_m;
    result.longitude_dev_deg_max = std::max(
        result.longitude_dev_deg_max,
        std::abs(std::remainder(std::atan2(r_E.y(), r_E.x()) - station_rad, 2 * std::numbers::pi)) / kDeg);
    result.inclination_deg_max = std::max(result.inclination_deg_max, osc.i.norm() / kDeg);
    if (const auto mean = filter.step(osc, t)) {
      result.eccentricity_max = std::max(result.eccentricity_max, mean->e.norm());
      StationKeepingInputs in;
      in.mean = *mean;
      in.failure = failure;
      in.sun_N_unit = sim::sunPosition_N_m(jd).normalized();
      in.dump_dv_m_s = 0.02;  // the rig's (station_keeping dump_dv_m_s)
      const auto plan = planner.step(in);
      pending = plan.firings;
    }
    double dt = kStep_s;
    for (const auto& firing : pending) dt = std::min(dt, secondsTo(firing));
    orbit.step(dt);
  }
  result.dv_m_s *= kYear_s / orbit.time_s();
  return result;
}

}  // namespace

TEST_CASE("S3 over a year at 75°E: every state holds the station box and fires outside the shadow", "[station_keeping][s3]") {
  const double v = 3074.66, cant = StationKeepingParams{}.thrusters.cant_rad;
  // The inclination alone costs v Δi / cos θ a year (0.94°/yr in 2027: 62 m/s
  // at θ = 36°; the typical 50 m/s of electric GEO station keeping is for
  // thrust along the normal).
  const double inclination_dv = v * 0.94 * kDeg / std::cos(cant);
  for (const auto failure : {PairFailure::kNone, PairFailure::k22_28, PairFailure::k20_30, PairFailure::k24_26}) {
    const YearResult r = flyYear(failure, 75.0 * kDeg);
    std::ostringstream firings;
    for (const auto& [thruster, count] : r.firings) firings << " " << thruster << ":" << count;
    WARN(nameOf(failure) << ": longitude " << r.longitude_dev_deg_max << " deg, i " << r.inclination_deg_max
                         << " deg, e " << r.eccentricity_max << ", dv " << r.dv_m_s << " m/s/yr, firings" << firings.str());
    CHECK(r.longitude_dev_deg_max < 0.05);
    CHECK(r.inclination_deg_max < 0.05);
    CHECK(r.eccentricity_max < 2e-4);
    CHECK(r.in_shadow == 0);
    for (const auto& [thruster, count] : r.firings) CHECK(available(static_cast<GeoThruster>(thruster), failure));
    CHECK(r.dv_m_s > 0.95 * inclination_dv);
    // A failed pair leaves firings whose thrust partly cancels (the diagonal
    // pair's radial parts, the centre pair's missing east–west reach).
    CHECK(r.dv_m_s < (failure == PairFailure::kNone ? 1.25 : 1.7) * inclination_dv);
  }
}

TEST_CASE("S3 over a year at 19.2°E and 105°E: every state, the box each holds", "[station_keeping][s3]") {
  // Away from the stable point J22 drives the longitude (0.0016°/day² east at
  // 19.2°E). Measured (the WARN lines print them) and pinned at 1.5×; where
  // the state holds the station box (±0.05°, 0.05°, 2e-4) that is asked too.
  // At 19.2°E the 20/30 and 24/26 failures do not: the one diagonal pair left
  // for the drift must push about 1.6 m/s a year more east than west, and
  // each such firing turns e as much as its drift is worth
  // (docs/s3_station_keeping.md).
  struct Measured {
    double longitude_deg, inclination_deg, eccentricity;
    bool holds_box;
  };
  const std::map<std::pair<double, PairFailure>, Measured> measured = {
      {{19.2, PairFailure::kNone}, {0.0305, 0.0125, 3.9e-5, true}},
      {{19.2, PairFailure::k22_28}, {0.0468, 0.0196, 1.12e-4, true}},
      {{19.2, PairFailure::k20_30}, {0.0533, 0.0271, 8.3e-5, false}},
      {{19.2, PairFailure::k24_26}, {0.0804, 0.0308, 9.3e-5, false}},
      {{105.0, PairFailure::kNone}, {0.0192, 0.0129, 3.8e-5, true}},
      {{105.0, PairFailure::k22_28}, {0.0319, 0.0203, 7.1e-5, true}},
      {{105.0, PairFailure::k20_30}, {0.0338, 0.0176, 5.0e-5, true}},
      {{105.0, PairFailure::k24_26}, {0.0290, 0.0172, 4.7e-5, true}}};
  for (const auto& [where, m] : measured) {
    const auto& [longitude_deg, failure] = where;
    const YearResult r = flyYear(failure, longitude_deg * kDeg);
    WARN(nameOf(failure) << " at " << longitude_deg << "E: longitude " << r.longitude_dev_deg_max << " deg, i "
                         << r.inclination_deg_max << " deg, e " << r.eccentricity_max << ", dv " << r.dv_m_s
                         << " m/s/yr");
    CHECK(r.longitude_dev_deg_max < 1.5 * m.longitude_deg);
    CHECK(r.inclination_deg_max < 1.5 * m.inclination_deg);
    CHECK(r.eccentricity_max < 1.5 * m.eccentricity);
    if (m.holds_box) {
      CHECK(r.longitude_dev_deg_max < 0.05);
      CHECK(r.inclination_deg_max < 0.05);
      CHECK(r.eccentricity_max < 2e-4);
    }
    CHECK(r.in_shadow == 0);
    for (const auto& [thruster, count] : r.firings) CHECK(available(static_cast<GeoThruster>(thruster), failure));
  }
}

TEST_CASE("S3 failure modes 2 and 3: NC(22) and SC(28) fired equally, as the seed has them, and each on its own",
          "[station_keeping][s3]") {
  // The seed fires the centre pair equally so that their radial parts cancel;
  // sized each on its own, the least squares may leave a radial part. Measured
  // (the WARN lines print them; docs/s3_station_keeping.md), pinned at 1.5×.
  // At 75°E, next to the stable point, the seed's way holds the box on 17 %
  // less ΔV; where J22 drives the longitude (19.2°E, 105°E) it leaves the box,
  // and each on its own holds it (105°E) or comes nearest (19.2°E).
  struct Year {
    double longitude_deg, inclination_deg, eccentricity, dv_m_s;
  };
  struct Both {
    Year equal, independent;
  };
  const std::map<std::pair<double, PairFailure>, Both> measured = {
      {{75.0, PairFailure::k20_30}, {{0.0280, 0.0250, 7.6e-5, 82.2}, {0.0376, 0.0193, 4.0e-5, 98.7}}},
      {{75.0, PairFailure::k24_26}, {{0.0280, 0.0230, 9.2e-5, 82.0}, {0.0426, 0.0224, 4.0e-5, 99.4}}},
      {{19.2, PairFailure::k20_30}, {{0.215, 0.123, 7.9e-4, 102.8}, {0.0533, 0.0271, 8.3e-5, 103.4}}},
      {{19.2, PairFailure::k24_26}, {{0.174, 0.116, 6.8e-4, 90.1}, {0.0804, 0.0308, 9.3e-5, 106.1}}},
      {{105.0, PairFailure::k20_30}, {{0.103, 0.0767, 7.2e-4, 101.4}, {0.0338, 0.0176, 5.0e-5, 106.9}}},
      {{105.0, PairFailure::k24_26}, {{0.0968, 0.104, 5.6e-4, 95.3}, {0.0290, 0.0172, 4.7e-5, 106.3}}}};
  const auto pinned = [](const YearResult& r, const Year& y) {
    CHECK(r.longitude_dev_deg_max < 1.5 * y.longitude_deg);
    CHECK(r.inclination_deg_max < 1.5 * y.inclination_deg);
    CHECK(r.eccentricity_max < 1.5 * y.eccentricity);
    CHECK(r.dv_m_s < 1.5 * y.dv_m_s);
    CHECK(r.dv_m_s > y.dv_m_s / 1.5);
    CHECK(r.in_shadow == 0);
  };
  for (const auto& [where, both] : measured) {
    const auto& [longitude_deg, failure] = where;
    const YearResult equal = flyYear(failure, longitude_deg * kDeg, true);
    const YearResult independent = flyYear(failure, longitude_deg * kDeg, false);
    WARN(nameOf(failure) << " at " << longitude_deg << "E, equal: longitude " << equal.longitude_dev_deg_max
                         << " deg, i " << equal.inclination_deg_max << " deg, e " << equal.eccentricity_max << ", dv "
                         << equal.dv_m_s << " m/s/yr; independent: longitude " << independent.longitude_dev_deg_max
                         << " deg, i " << independent.inclination_deg_max << " deg, e "
                         << independent.eccentricity_max << ", dv " << independent.dv_m_s << " m/s/yr");
    pinned(equal, both.equal);
    pinned(independent, both.independent);
    if (longitude_deg == 75.0) {
      CHECK(equal.longitude_dev_deg_max < 0.05);
      CHECK(equal.dv_m_s < 0.9 * independent.dv_m_s);
    } else {
      CHECK(equal.longitude_dev_deg_max > 0.05);
      CHECK(independent.longitude_dev_deg_max < equal.longitude_dev_deg_max / 2);
    }
  }
}
