// SPDX-License-Identifier: Apache-2.0
// Seed S3's planner: one orbit's firings from the mean elements. Reference:
// the exact two-body elements after the planned impulses are given at their
// right ascensions, which must be what the plan says it leaves, and, where
// the table's thrusters can do it, the targets.
#include <cmath>
#include <numbers>

#include <catch2/catch.hpp>

#include "components/station_keeping/StationKeepingPlanner.hpp"
#include "sim/Constants.hpp"
#include "sim/KeplerOrbit.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat;
using namespace flatsat::station_keeping;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {

constexpr double kGmst0 = 0.3;  // [rad] Greenwich at t = 0
const double kOmega = sim::kEarthRotationRate_rad_s;

/// The two-body orbit with these synchronous elements at t = 0.
sim::OrbitElements classical(const SynchronousElements& s) {
  sim::OrbitElements k;
  const double n = kOmega + s.drift_rad_s;
  k.semi_major_axis_m = std::cbrt(sim::kMuEarth_m3_s2 / (n * n));
  k.eccentricity = s.e.norm();
  k.inclination_rad = s.i.norm();
  k.raan_rad = std::atan2(s.i.x(), -s.i.y());
  const double perigee = std::atan2(s.e.y(), s.e.x());
  k.arg_perigee_rad = perigee - k.raan_rad;
  k.mean_anomaly_rad = s.longitude_rad + kGmst0 - perigee;
  return k;
}

/// Flies one orbit from `start`, giving each planned firing as an impulse when
/// the spacecraft's right ascension is the firing's; the elements after it.
SynchronousElements fly(const SynchronousElements& start, const StationKeepingPlan& plan, const GeoThrusterParams& t) {
  auto firings = plan.firings;
  const double l0 = start.longitude_rad + kGmst0;
  const auto when = [&](const PlannedFiring& f) {
    return std::fmod(std::fmod(f.ra_rad - l0, 2 * std::numbers::pi) + 2 * std::numbers::pi, 2 * std::numbers::pi);
  };
  std::sort(firings.begin(), firings.end(), [&](const auto& a, const auto& b) { return when(a) < when(b); });
  SynchronousElements now = start;
  double t_now = 0.0;
  for (const auto& f : firings) {
    const double t_fire = when(f) / kOmega;
    // The elements are those of an orbit whose epoch is t_now.
    const sim::KeplerOrbit orbit(classical(now));
    const auto state = orbit.at(t_fire - t_now);
    const Eigen::Vector3d d = f.dv_m_s * forceDirection_orbital(f.thruster, t);
    // Re-based at t_fire: the longitude taken against kGmst0, which classical() adds back,
    // makes `now` the elements of an orbit whose epoch is t_fire.
    now = synchronousElements(state.r_N_m, state.v_N_m_s + R_N_orbital(state.r_N_m, state.v_N_m_s) * d, kGmst0);
    t_now = t_fire;
  }
  return now;
}

SynchronousElements aDayOfDrift(double station_rad) {
  SynchronousElements s;
  s.longitude_rad = station_rad + 0.004 * kDeg;
  s.drift_rad_s = 5e-11;  // 0.00025°/day east
  s.i = 2.6e-5 * Eigen::Vector2d(std::cos(9 * kDeg), -std::sin(9 * kDeg));  // 0.0015°: a day of the Sun and Moon
  s.e = Eigen::Vector2d(3e-6, -5e-6);
  return s;
}

}  // namespace

TEST_CASE("S3 planner: parameters are checked, naming the field", "[station_keeping][s3]") {
  StationKeepingParams p;
  p.thrust_N = 0.0;
  p.thrusters.cant_rad = 2.0;
  try {
    StationKeepingPlanner planner(p);
    FAIL("accepted");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(e.what(), Catch::Matchers::Contains("thrust_N: outside (0, 2] N"));
    CHECK_THAT(e.what(), Catch::Matchers::Contains("thrusters.cant_rad:"));
  }
}

TEST_CASE("S3 planner: nominal firings bring i and e to zero and the drift to the return drift, as flown", "[station_keeping][s3]") {
  StationKeepingParams p;
  p.station_longitude_rad = 19.2 * kDeg;
  // A slow return, so that a day's small inclination firings (whose
  // difference carries the drift and e) can meet every target at once.
  p.longitude_return_s = 10 * 86400.0;
  const StationKeepingPlanner planner(p);
  StationKeepingInputs in;
  in.mean = aDayOfDrift(p.station_longitude_rad);
  in.sun_N_unit = Eigen::Vector3d(std::cos(60 * kDeg), std::sin(60 * kDeg) * 0.917, std::sin(60 * kDeg) * 0.398).normalized();
  for (const double dump : {0.0, 0.01}) {
    CAPTURE(dump);
    in.dump_dv_m_s = dump;
    const StationKeepingPlan plan = planner.step(in);
    // Only the table's thrusters; the outer four and, with a dump, the centre pair.
    REQUIRE_FALSE(plan.firings.empty());
    for (const auto& f : plan.firings) {
      CHECK(f.dv_m_s > 0.0);
      CHECK_THAT(f.duration_s, WithinAbs(f.dv_m_s * p.mass_kg / p.thrust_N, 1e-9));
    }
    const double v = 3074.66;
    // The i firings turn in 2.5° steps: what is left of i is at most the
    // sine of half a step of it; e and the drift are met.
    CHECK(plan.i_after.norm() < std::sin(1.25 * kDeg) * in.mean.i.norm());
    CHECK(plan.e_after.norm() < 1e-2 * in.mean.e.norm());
    CHECK_THAT(plan.drift_after_rad_s, WithinAbs(plan.drift_target_rad_s, 1e-2 * std::abs(in.mean.drift_rad_s)));
    // The return drift: the longitude error, after the radial parts' jumps
    // (−2 ΔV_R / v each), over longitude_return_s.
    double jump = 0.0;
    for (const auto& f : plan.firings) jump -= 2.0 * f.dv_m_s * forceDirection_orbital(f.thruster, p.thrusters).z() / v;
    CHECK_THAT(plan.longitude_jump_rad, WithinRel(jump, 1e-5));
    CHECK_THAT(plan.drift_target_rad_s, WithinAbs(-(0.004 * kDeg + jump) / p.longitude_return_s, 1e-18));
    // About v |Δi| for the inclination, the rest small.
    CHECK(plan.dv_total_m_s > v * in.mean.i.norm() / std::cos(p.thrusters.cant_rad) * 0.99);
    const SynchronousElements flown = fly(in.mean, plan, p.thrusters);
    CHECK((flown.i - plan.i_after).norm() < 1e-3 * in.mean.i.norm());
    CHECK((flown.e - plan.e_after).norm() < 2e-2 * in.mean.e.norm());
    CHECK_THAT(flown.drift_rad_s, WithinAbs(plan.drift_after_rad_s, 1e-2 * std::abs(in.mean.drift_rad_s)));
  }
}

TEST_CASE("S3 planner: with a pair failed, only the table's thrusters fire and the errors shrink",
          "[station_keeping][s3]") {
  StationKeepingParams p;
  const StationKeepingPlanner planner(p);
  for (const auto failure : {PairFailure::k22_28, PairFailure::k20_30, PairFailure::k24_26}) {
    for (const double sun_ra_deg : {0.0, 45.0, 135.0, 180.0, 225.0, 315.0}) {
      StationKeepingInputs in;
      in.mean = aDayOfDrift(0.0);
      in.failure = failure;
      const double dec = 23.44 * kDeg * std::sin(sun_ra_deg * kDeg);
      in.sun_N_unit = {std::cos(dec) * std::cos(sun_ra_deg * kDeg), std::cos(dec) * std::sin(sun_ra_deg * kDeg),
                       std::sin(dec)};
      const StationKeepingPlan plan = planner.step(in);
      CAPTURE(nameOf(failure), sun_ra_deg);
      for (const auto& f : plan.firings) CHECK(available(f.thruster, failure));
      // The plan weighs each error by its share of the box and may leave some
      // i for the next orbit when the firings that carry the drift turn i too.
      CHECK(plan.i_after.norm() < in.mean.i.norm());
      // Weighed by the box, it leaves less error than doing nothing.
      const auto weighed = [&](const Eigen::Vector2d& i, const Eigen::Vector2d& e, double drift) {
        return std::hypot(i.norm() / p.box_inclination_rad, e.norm() / p.box_eccentricity,
                          (drift - plan.drift_target_rad_s) * p.drift_horizon_s / p.box_longitude_rad);
      };
      CHECK(weighed(plan.i_after, plan.e_after, plan.drift_after_rad_s) <
            weighed(in.mean.i, in.mean.e, in.mean.drift_rad_s));
      const SynchronousElements flown = fly(in.mean, plan, p.thrusters);
      CHECK((flown.i - plan.i_after).norm() < 2e-3 * in.mean.i.norm());
      CHECK((flown.e - plan.e_after).norm() < 5e-2 * in.mean.e.norm());
    }
  }
}

TEST_CASE("S3 planner: each MD firing flies as two halves whose thrust lines part, so its gimbals reach every "
          "direction",
          "[station_keeping][s3]") {
  // A gimbal turns a thrust line through the centre of mass only within the
  // plane normal to it: firings whose lines are all parallel leave the
  // momentum along that line undumped. NC(22) at 90° and SC(28) at 270° share
  // one inertial line; halves at ±δ part by the angle whose cosine is
  // cos²θ + sin²θ cos 2δ (θ the cant: the zenith part of the line turns by 2δ).
  const auto inertial = [](const PlannedFiring& f, const GeoThrusterParams& t) {
    const Eigen::Vector3d d = forceDirection_orbital(f.thruster, t);
    const double c = std::cos(f.ra_rad), s = std::sin(f.ra_rad);
    return Eigen::Vector3d(d.x() * -s + d.z() * c, d.x() * c + d.z() * s, d.y());
  };
  const auto widestParting = [&](const StationKeepingPlan& plan, const GeoThrusterParams& t) {
    double widest = 0.0;
    for (const auto& a : plan.firings) {
      for (const auto& b : plan.firings) {
        if (dumpsMomentum(a.job) && dumpsMomentum(b.job)) widest = std::max(widest, inertial(a, t).cross(inertial(b, t)).norm());
      }
    }
    return widest;
  };
  StationKeepingInputs in;
  in.mean = aDayOfDrift(0.0);
  in.dump_dv_m_s = 0.02;
  for (const auto failure : {PairFailure::kNone, PairFailure::k22_28, PairFailure::k20_30, PairFailure::k24_26}) {
    for (const double sun_ra_deg : {45.0, 225.0}) {
      in.failure = failure;
      in.sun_N_unit = {std::cos(sun_ra_deg * kDeg), std::sin(sun_ra_deg * kDeg), 0.0};
      StationKeepingParams p;
      const StationKeepingPlan plan = StationKeepingPlanner(p).step(in);
      CAPTURE(nameOf(failure), sun_ra_deg);
      REQUIRE(plan.firings.size() <= 8);  // what the plan topic carries
      // Halves: the same thruster and size, 2δ apart.
      int halves = 0;
      for (std::size_t k = 0; k + 1 < plan.firings.size(); ++k) {
        const auto &a = plan.firings[k], &b = plan.firings[k + 1];
        if (!dumpsMomentum(a.job)) continue;
        CHECK(b.thruster == a.thruster);
        CHECK_THAT(b.dv_m_s, WithinRel(a.dv_m_s, 1e-12));
        CHECK_THAT(std::remainder(b.ra_rad - a.ra_rad, 2 * std::numbers::pi), WithinAbs(2 * p.dump_arc_rad, 1e-12));
        ++halves;
        ++k;
      }
      CHECK(halves >= 1);  // a day whose i wants one node has one
      const double c = std::cos(p.thrusters.cant_rad), s = std::sin(p.thrusters.cant_rad);
      const double parting = std::sqrt(1.0 - std::pow(c * c + s * s * std::cos(2 * p.dump_arc_rad), 2));
      CHECK(widestParting(plan, p.thrusters) > parting - 1e-9);
      if (failure == PairFailure::kNone) {
        CHECK_THAT(widestParting(plan, p.thrusters), WithinAbs(parting, 1e-9));  // ≈ 2 sin θ sin δ = 0.30
        p.dump_arc_rad = 0.0;
        CHECK(widestParting(StationKeepingPlanner(p).step(in), p.thrusters) < 1e-12);
      }
    }
  }
}
