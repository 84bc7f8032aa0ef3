// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <functional>

#include <catch2/catch.hpp>

#include "sim/OrbitPropagator.hpp"
#include "sim/SunEphemeris.hpp"
#include "tests/support/TestUnits.hpp"
#include "tests/unit/sim/OrbitState.hpp"

using namespace flatsat::sim;

namespace {

using State = OrbitPropagator::State;

OrbitForceParams centralGravityOnly() {
  OrbitForceParams p;
  p.j2 = p.j3 = p.j4 = p.drag = p.solar_pressure = p.sun_gravity = p.moon_gravity = false;
  return p;
}

using test::semiMajorAxis;

// [s] Instant in [t0, t0 + dt] where `inside` turns from false to true or back, by
// bisection on copies of the propagator taken at t0.
double crossing(const OrbitPropagator& at_t0, double dt, const std::function<bool(const State&)>& inside) {
  const bool start = inside(at_t0.state());
  double lo = 0.0;
  double hi = dt;
  while (hi - lo > 1e-3) {
    const double mid = 0.5 * (lo + hi);
    OrbitPropagator probe = at_t0;
    probe.step(mid);
    (inside(probe.state()) == start ? lo : hi) = mid;
  }
  return at_t0.time_s() + 0.5 * (lo + hi);
}

}  // namespace

TEST_CASE("eclipse entry and exit along the orbit match the shadow cylinder", "[sim][orbit]") {
  // Circular equatorial orbit at 700 km starting at +x; the Sun fixed at β = 20°
  // above the orbit plane, in the x–z plane. Then r̂·ŝ = cos β cos u, and the
  // distance from the shadow axis r √(1 − cos²β cos²u) equals R at
  // u = π ∓ arccos(√(1 − R²/r²) / cos β) (cylindrical shadow).
  const double R = kEarthEquatorialRadius_m;
  const double r = R + 700e3;
  const double beta = 20.0 * kDeg;
  const Eigen::Vector3d sun = kAstronomicalUnit_m * Eigen::Vector3d(std::cos(beta), 0.0, std::sin(beta));
  const KeplerOrbit kepler(OrbitElements{r, 0.0, 0.0, 0.0, 0.0, 0.0});
  const double n = kepler.meanMotion_rad_s();
  const double half_width = std::acos(std::sqrt(1.0 - R * R / (r * r)) / std::cos(beta));
  const double t_entry = (kPi - half_width) / n;
  const double t_exit = (kPi + half_width) / n;

  OrbitPropagator propagator(centralGravityOnly(), UtcEpoch{}, kepler.at(0.0));
  auto inShadowHalf = [&](const State& s) { return illumination(s.r_N_m, sun) < 0.5; };
  auto inPenumbra = [&](const State& s) { return illumination(s.r_N_m, sun) < 1.0; };
  auto inUmbra = [&](const State& s) { return illumination(s.r_N_m, sun) == 0.0; };
  double half_entry = -1.0, half_exit = -1.0, penumbra_entry = -1.0, umbra_entry = -1.0;
  const double dt = 10.0;
  while (propagator.time_s() < kepler.period_s()) {
    const OrbitPropagator before = propagator;
    propagator.step(dt);
    const State& s0 = before.state();
    const State& s1 = propagator.state();
    if (inShadowHalf(s0) != inShadowHalf(s1)) {
      (inShadowHalf(s1) ? half_entry : half_exit) = crossing(before, dt, inShadowHalf);
    }
    if (!inPenumbra(s0) && inPenumbra(s1)) penumbra_entry = crossing(before, dt, inPenumbra);
    if (!inUmbra(s0) && inUmbra(s1)) umbra_entry = crossing(before, dt, inUmbra);
  }
  INFO("cylinder " << t_entry << " / " << t_exit << " s; half-light " << half_entry << " / " << half_exit << " s");
  THEN("the half-light instants are the cylinder's within 1 s") {
    CHECK(std::abs(half_entry - t_entry) < 1.0);
    CHECK(std::abs(half_exit - t_exit) < 1.0);
  }
  THEN("the penumbra lasts 2 x α/ρ̇: x the depth behind the Earth, α the Sun's angular radius") {
    const double cos_u = std::cos(n * t_entry);
    const double sin_u = std::sin(n * t_entry);
    const double depth = r * std::cos(beta) * std::abs(cos_u);
    const double rho_rate = r * r * std::cos(beta) * std::cos(beta) * std::abs(cos_u * sin_u) * n / R;
    const double expected = 2.0 * depth * (kSunRadius_m / kAstronomicalUnit_m) / rho_rate;
    CHECK(penumbra_entry < half_entry);
    CHECK(half_entry < umbra_entry);
    CHECK(umbra_entry - penumbra_entry == Approx(expected).epsilon(0.1));
  }
}

TEST_CASE("drag lowers a circular orbit at the closed-form rate", "[sim][orbit]") {
  // Equatorial prograde circular orbit at 420 km, exponential atmosphere (constant
  // along the orbit: no bulge, the equator is at constant ellipsoid height).
  // Gauss: da/dt = 2 a^(3/2) a_T / √μ with a_T = −½ ρ B v_rel², so
  // da/dt = −ρ B √(μ a) (1 − ω a / v)²: the brief's −ρ B √(μ a) reduced by the
  // air co-rotating with the Earth at ω a along the velocity.
  OrbitForceParams params = centralGravityOnly();
  params.drag = true;
  params.atmosphere.model = DensityModel::kExponential;
  const double b = params.drag_coefficient * params.drag_area_m2 / params.mass_kg;
  const double a0 = kEarthEquatorialRadius_m + 420e3;
  OrbitPropagator propagator(params, UtcEpoch{}, KeplerOrbit(OrbitElements{a0, 0.0, 0.0, 0.0, 0.0, 0.0}).at(0.0));
  const double day = 86400.0;
  for (int k = 0; k < 2880; ++k) propagator.step(30.0);

  // The closed form integrated over the day by RK4; Vallado Table 8-4, 400–450 km band.
  auto rate = [&](double a) {
    const double rho = 3.725e-12 * std::exp(-(a - kEarthEquatorialRadius_m - 400e3) / 58.515e3);
    const double corotation = 1.0 - 7.292115e-5 * a / std::sqrt(kMu / a);
    return -rho * b * std::sqrt(kMu * a) * corotation * corotation;
  };
  double a = a0;
  const double h = day / 100.0;
  for (int k = 0; k < 100; ++k) {
    const double k1 = rate(a), k2 = rate(a + 0.5 * h * k1), k3 = rate(a + 0.5 * h * k2), k4 = rate(a + h * k3);
    a += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  const double measured = semiMajorAxis(propagator.state()) - a0;
  INFO("decay in one day: propagated " << measured << " m, closed form " << a - a0 << " m");
  CHECK(measured == Approx(a - a0).epsilon(0.01));
}

TEST_CASE("OrbitPropagator with every force stays a sensible low orbit", "[sim][orbit]") {
  const UtcEpoch epoch{2026, 3, 1, 0, 0, 0.0};
  const double a0 = kEarthEquatorialRadius_m + 500e3;
  const State s0 = KeplerOrbit(OrbitElements{a0, 0.001, 97.4 * kDeg, 40.0 * kDeg, 0.0, 0.0}).at(0.0);
  const OrbitForceParams all;
  OrbitPropagator propagator(all, epoch, s0);
  GIVEN("the acceleration at the epoch") {
    THEN("it is OrbitForces' with the ephemerides of TT = UTC + 69.184 s") {
      const OrbitForces forces(all);
      const double jd_tt = julianDate(epoch) + 69.184 / 86400.0;
      const Eigen::Vector3d expected = forces.acceleration_N(s0.r_N_m, s0.v_N_m_s, forces.ephemeridesAt(jd_tt));
      CHECK((propagator.acceleration_N(0.0, s0) - expected).norm() < 1e-15 * expected.norm());
    }
  }
  GIVEN("one day at 30 s steps") {
    OrbitForceParams no_drag = all;
    no_drag.drag = false;
    OrbitPropagator reference(no_drag, epoch, s0);
    for (int k = 0; k < 2880; ++k) {
      propagator.step(30.0);
      reference.step(30.0);
    }
    THEN("the state is finite and the orbit keeps its size within the J2 short-period swing") {
      CHECK(propagator.state().r_N_m.allFinite());
      CHECK(std::abs(semiMajorAxis(propagator.state()) - a0) < 20e3);
    }
    THEN("drag has taken energy: the orbit is lower, hence faster and ahead of the drag-free one") {
      CHECK(semiMajorAxis(propagator.state()) < semiMajorAxis(reference.state()));
      const Eigen::Vector3d along = reference.state().v_N_m_s.normalized();
      CHECK((propagator.state().r_N_m - reference.state().r_N_m).dot(along) > 0.0);
    }
  }
}
