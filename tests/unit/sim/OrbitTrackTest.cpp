// SPDX-License-Identifier: Apache-2.0
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "sim/OrbitTrack.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;
using Catch::Matchers::Contains;

namespace {

const OrbitElements kLeo{kEarthEquatorialRadius_m + 560e3, 0.001, 53.0 * kDeg, 40.0 * kDeg, 10.0 * kDeg, 0.0};
const UtcEpoch kEpoch{2026, 3, 20, 0, 0, 0.0};

OrbitTrackParams numerical(double step_s, bool perturbed) {
  OrbitTrackParams p;
  p.propagator = OrbitPropagation::kNumerical;
  p.step_s = step_s;
  OrbitForceParams& f = p.forces;
  f.j2 = f.j3 = f.j4 = f.drag = f.solar_pressure = f.sun_gravity = f.moon_gravity = perturbed;
  f.mass_kg = 2400.0;
  f.drag_area_m2 = 20.0;
  f.srp_area_m2 = 15.0;
  return p;
}

bool sameBits(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

}  // namespace

TEST_CASE("OrbitTrack follows the Kepler orbit in its Kepler mode", "[sim][orbit]") {
  OrbitTrack track(OrbitTrackParams{}, kLeo, kEpoch);
  const KeplerOrbit kepler(kLeo);
  for (const double t : {0.0, 0.1, 1234.5, 5000.0}) {
    CHECK(sameBits(track.at(t).r_N_m, kepler.at(t).r_N_m));
    CHECK(sameBits(track.at(t).v_N_m_s, kepler.at(t).v_N_m_s));
  }
  WHEN("it is kicked") {
    track.kick(100.0, Eigen::Vector3d::Ones(), Eigen::Vector3d::Ones());
    THEN("nothing changes: thrust does not move a Kepler orbit") {
      CHECK(sameBits(track.at(200.0).r_N_m, kepler.at(200.0).r_N_m));
    }
  }
}

TEST_CASE("OrbitTrack interpolates the numerical orbit between its grid points", "[sim][orbit]") {
  GIVEN("two-body motion, whose exact solution is the Kepler orbit") {
    const KeplerOrbit kepler(kLeo);
    for (const double step_s : {10.0, 60.0}) {
      CAPTURE(step_s);
      OrbitTrack track(numerical(step_s, false), kLeo, kEpoch);
      double position_error = 0.0;
      double velocity_error = 0.0;
      // 0.7 s queries fall everywhere inside the grid intervals, over one orbit.
      for (double t = 0.0; t <= kepler.period_s(); t += 0.7) {
        const OrbitTrack::State s = track.at(t);
        position_error = std::max(position_error, (s.r_N_m - kepler.at(t).r_N_m).norm());
        velocity_error = std::max(velocity_error, (s.v_N_m_s - kepler.at(t).v_N_m_s).norm());
      }
      // The class comment's bounds: h⁴|r⁽⁴⁾|/384 and h³|r⁽⁴⁾|/125, |r⁽⁴⁾| ≈ n⁴ r ≈ 1.0e-5 m/s⁴.
      const double r4 = std::pow(kepler.meanMotion_rad_s(), 4) * kLeo.semi_major_axis_m;
      CHECK(position_error < std::pow(step_s, 4) * r4 / 384.0 * 1.1 + 1e-3);
      CHECK(velocity_error < std::pow(step_s, 3) * r4 / 125.0 * 1.1 + 1e-6);
      if (step_s == 10.0) {
        CHECK(position_error < 1e-3);  // [m]
        CHECK(velocity_error < 1e-4);  // [m/s]
      }
    }
  }
  GIVEN("every force on") {
    OrbitTrack track(numerical(10.0, true), kLeo, kEpoch);
    OrbitPropagator reference(numerical(10.0, true).forces, kEpoch, KeplerOrbit(kLeo).at(0.0));
    THEN("the grid points are the propagator's own steps, bit for bit") {
      for (int j = 1; j <= 50; ++j) {
        reference.step(10.0);
        track.at(10.0 * j - 3.3);  // from inside the interval, as a caller would
        const OrbitTrack::State s = track.at(10.0 * j);
        CHECK(sameBits(s.r_N_m, reference.state().r_N_m));
        CHECK(sameBits(s.v_N_m_s, reference.state().v_N_m_s));
      }
    }
    THEN("reset() starts the same orbit again") {
      const Eigen::Vector3d r = track.at(777.7).r_N_m;
      track.reset();
      CHECK(sameBits(track.at(0.0).r_N_m, KeplerOrbit(kLeo).at(0.0).r_N_m));
      CHECK(sameBits(track.at(777.7).r_N_m, r));
    }
  }
}

TEST_CASE("OrbitTrack kicks restart the integration and keep the grid", "[sim][orbit]") {
  const OrbitTrackParams params = numerical(10.0, false);
  OrbitTrack track(params, kLeo, kEpoch);
  const double t_kick = 123.4;
  track.at(t_kick);
  // The state at the kick, integrated over the grid to 120 s and on to the kick.
  OrbitPropagator exact(params.forces, kEpoch, KeplerOrbit(kLeo).at(0.0));
  for (int j = 0; j < 12; ++j) exact.step(10.0);
  exact.step(t_kick - 120.0);
  const OrbitTrack::State before = exact.state();
  const Eigen::Vector3d dv = 0.05 * before.v_N_m_s.normalized();  // 5 cm/s prograde
  track.kick(t_kick, Eigen::Vector3d::Zero(), dv);

  THEN("the state at the kick carries it") {
    CHECK(((track.at(t_kick).v_N_m_s - before.v_N_m_s) - dv).norm() < 1e-12);
  }
  THEN("later states are those of a propagator started from the kicked state") {
    OrbitPropagator reference(params.forces, kEpoch, OrbitPropagator::State{before.r_N_m, before.v_N_m_s + dv});
    reference.restart(t_kick, OrbitPropagator::State{before.r_N_m, before.v_N_m_s + dv});
    reference.step(130.0 - t_kick);  // to the next grid point
    CHECK((track.at(130.0).r_N_m - reference.state().r_N_m).norm() < 1e-9);
    reference.step(10.0);
    CHECK((track.at(140.0).r_N_m - reference.state().r_N_m).norm() < 1e-9);
  }
  THEN("the orbital energy grows by v·Δv (vis-viva)") {
    const auto energy = [](const OrbitTrack::State& s) {
      return 0.5 * s.v_N_m_s.squaredNorm() - kMuEarth_m3_s2 / s.r_N_m.norm();
    };
    CHECK(energy(track.at(2000.0)) - energy(before) == Approx(before.v_N_m_s.dot(dv)).epsilon(1e-4));
  }
  WHEN("a kick falls on a grid point") {
    const OrbitTrack::State on_grid = track.at(150.0);
    track.kick(150.0, Eigen::Vector3d::Zero(), dv);
    THEN("the next interval starts there") {
      CHECK(((track.at(150.0).v_N_m_s - on_grid.v_N_m_s) - dv).norm() < 1e-12);
      CHECK((track.at(150.0).r_N_m - on_grid.r_N_m).norm() == 0.0);
      CHECK(track.at(155.0).r_N_m.allFinite());
    }
  }
}

TEST_CASE("OrbitTrackParams::validate checks the numerical set-up only", "[sim][orbit]") {
  OrbitTrackParams kepler;
  kepler.step_s = -1.0;
  kepler.forces.mass_kg = 0.0;
  CHECK(kepler.validate().empty());

  OrbitTrackParams p = numerical(0.0, true);
  p.forces.mass_kg = -1.0;
  const auto errors = p.validate();
  REQUIRE(errors.size() == 2);
  CHECK_THAT(errors[0], Contains("step_s: 0 s must be in (0, 600]"));
  CHECK_THAT(errors[1], Contains("forces.mass_kg"));
  CHECK_THROWS_WITH(OrbitTrack(p, kLeo, kEpoch), Contains("step_s") && Contains("forces.mass_kg"));
  OrbitElements bad = kLeo;
  bad.eccentricity = 2.0;
  CHECK_THROWS_WITH(OrbitTrack(OrbitTrackParams{}, bad, kEpoch), Contains("elements.eccentricity"));
}
