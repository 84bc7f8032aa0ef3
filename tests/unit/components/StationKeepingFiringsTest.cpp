// SPDX-License-Identifier: Apache-2.0
// The sequencer's station-keeping mode (seed S3): each planned firing flown as
// a finite burn centred on its right ascension; plans replace what has not
// begun.
#include <cmath>

#include <catch2/catch.hpp>

#include "components/thruster_sequencer/StationKeepingFirings.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::thruster_sequencer;

namespace {

constexpr double kRate = 7.2921e-5;  // [rad/s]

struct Flown {
  double on_s = 0.0;       // total on-time of thruster 1
  double centre_deg = 0.0; // on-time-weighted right ascension
};

/// Steps of 60 s from right ascension ra0_deg for `steps`, thruster 1's burn.
Flown fly(StationKeepingFirings& firings, double ra0_deg, int steps) {
  Flown out;
  double weighted = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double ra = ra0_deg * kDeg + k * 60.0 * kRate;
    const double on = firings.step(ra).on_time_s(1);
    // The step's on-time is flown from its start: its centre is half of it on.
    weighted += on * (ra + 0.5 * on * kRate);
    out.on_s += on;
  }
  out.centre_deg = out.on_s > 0.0 ? weighted / out.on_s / kDeg : 0.0;
  return out;
}

}  // namespace

TEST_CASE("S3 firings: a burn is flown whole, centred on its right ascension", "[thruster_sequencer][s3]") {
  StationKeepingFirings firings({60.0, kRate, 6});
  firings.plan(100, {{1, 90.0 * kDeg, 3000.0}});
  const Flown f = fly(firings, 40.0, 1440);
  CHECK(f.on_s == Approx(3000.0).epsilon(1e-12));
  // Started at the first step past 90° − 1500 s of arc: within a step's sweep (0.25°).
  CHECK(f.centre_deg == Approx(90.0).margin(0.26));
  // The same plan again fires nothing more.
  firings.plan(100, {{1, 90.0 * kDeg, 3000.0}});
  CHECK(fly(firings, 40.0, 1440).on_s == 0.0);
}

TEST_CASE("S3 firings: a new plan replaces the firings not begun, a burn under way runs to its end", "[thruster_sequencer][s3]") {
  StationKeepingFirings firings({60.0, kRate, 6});
  firings.plan(1, {{1, 90.0 * kDeg, 1200.0}, {2, 200.0 * kDeg, 600.0}});
  // Into thruster 1's burn: 90° − 600 s of arc is 87.5°; 10 minutes of it flown.
  const double start = 87.5 + 0.01;
  double flown = 0.0;
  for (int k = 0; k < 10; ++k) flown += firings.step((start + k * 60.0 * kRate / kDeg) * kDeg).on_time_s(1);
  CHECK(flown == Approx(600.0));
  firings.plan(2, {{3, 300.0 * kDeg, 60.0}});
  double rest = 0.0, thruster2 = 0.0, thruster3 = 0.0;
  for (int k = 10; k < 1440; ++k) {
    const auto on = firings.step((start + k * 60.0 * kRate / kDeg) * kDeg).on_time_s;
    rest += on(1);
    thruster2 += on(2);
    thruster3 += on(3);
  }
  CHECK(rest == Approx(600.0));   // the burn under way ran to its end
  CHECK(thruster2 == 0.0);        // the old plan's later firing was dropped
  CHECK(thruster3 == Approx(60.0));
}

TEST_CASE("S3 firings: a plan that comes inside an arc starts at once up to its centre, else waits", "[thruster_sequencer][s3]") {
  StationKeepingFirings before_centre({60.0, kRate, 6});
  before_centre.plan(1, {{1, 90.0 * kDeg, 3600.0}});  // arc 82.5°..97.5°
  CHECK(before_centre.step(85.0 * kDeg).on_time_s(1) == 60.0);
  StationKeepingFirings past_centre({60.0, kRate, 6});
  past_centre.plan(1, {{1, 90.0 * kDeg, 3600.0}});
  CHECK(past_centre.step(92.0 * kDeg).on_time_s(1) == 0.0);
  CHECK_THROWS_WITH(StationKeepingFirings({0.0, kRate, 6}), Catch::Matchers::Contains("step_s"));
}
