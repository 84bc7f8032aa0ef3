// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/OrbitPropagator.hpp"
#include "sim/SunEphemeris.hpp"
#include "tests/support/TestUnits.hpp"
#include "tests/unit/sim/OrbitState.hpp"

using namespace flatsat::sim;

namespace {

using State = OrbitPropagator::State;

OrbitForceParams gravityOnly(bool j2) {
  OrbitForceParams p;
  p.j2 = j2;
  p.j3 = p.j4 = p.drag = p.solar_pressure = p.sun_gravity = p.moon_gravity = false;
  return p;
}

using test::energy;
using test::semiMajorAxis;
Eigen::Vector3d angularMomentum(const State& s) { return s.r_N_m.cross(s.v_N_m_s); }
double raan(const State& s) {
  const Eigen::Vector3d h = angularMomentum(s);
  return std::atan2(h.x(), -h.y());
}
double inclination(const State& s) {
  const Eigen::Vector3d h = angularMomentum(s);
  return std::acos(h.z() / h.norm());
}

// [m] Position error after one revolution of a two-body orbit at step period/steps.
double oneRevolutionError(const OrbitElements& elements, int steps) {
  const KeplerOrbit kepler(elements);
  OrbitPropagator propagator(gravityOnly(false), UtcEpoch{}, kepler.at(0.0));
  const double dt = kepler.period_s() / steps;
  for (int i = 0; i < steps; ++i) propagator.step(dt);
  return (propagator.state().r_N_m - kepler.at(propagator.time_s()).r_N_m).norm();
}

// Least-squares slope of y(t).
double slope(const std::vector<double>& t, const std::vector<double>& y) {
  const double n = static_cast<double>(t.size());
  double st = 0.0, sy = 0.0, stt = 0.0, sty = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    st += t[i];
    sy += y[i];
    stt += t[i] * t[i];
    sty += t[i] * y[i];
  }
  return (n * sty - st * sy) / (n * stt - st * st);
}

}  // namespace

TEST_CASE("OrbitPropagator conserves the two-body integrals", "[sim][orbit]") {
  const OrbitElements elements{8000e3, 0.1, 51.6 * kDeg, 30.0 * kDeg, 45.0 * kDeg, 10.0 * kDeg};
  const KeplerOrbit kepler(elements);
  GIVEN("ten revolutions at 200 steps per revolution (36 s)") {
    OrbitPropagator propagator(gravityOnly(false), UtcEpoch{}, kepler.at(0.0));
    const State s0 = propagator.state();
    const double dt = kepler.period_s() / 200.0;
    double worst_energy = 0.0;
    double worst_momentum = 0.0;
    for (int i = 0; i < 2000; ++i) {
      propagator.step(dt);
      worst_energy = std::max(worst_energy, std::abs(energy(propagator.state()) / energy(s0) - 1.0));
      worst_momentum = std::max(worst_momentum, (angularMomentum(propagator.state()) - angularMomentum(s0)).norm() /
                                                    angularMomentum(s0).norm());
    }
    THEN("energy and angular momentum hold to 1e-10 (relative)") {
      CHECK(worst_energy < 1e-10);
      CHECK(worst_momentum < 1e-10);
    }
    THEN("the state agrees with the Kepler solution to 1 mm and 1 µm/s") {
      const KeplerOrbit::State exact = kepler.at(propagator.time_s());
      CHECK((propagator.state().r_N_m - exact.r_N_m).norm() < 1e-3);
      CHECK((propagator.state().v_N_m_s - exact.v_N_m_s).norm() < 1e-6);
    }
  }
}

TEST_CASE("OrbitPropagator converges with order 8", "[sim][orbit]") {
  const OrbitElements elements{8000e3, 0.1, 51.6 * kDeg, 30.0 * kDeg, 45.0 * kDeg, 10.0 * kDeg};
  GIVEN("one two-body revolution at 20, 40 and 80 steps") {
    const double e20 = oneRevolutionError(elements, 20);
    const double e40 = oneRevolutionError(elements, 40);
    const double e80 = oneRevolutionError(elements, 80);
    THEN("each halving of the step divides the error by 2⁸ = 256 (observed order 8 ± 0.5)") {
      CHECK(std::log2(e20 / e40) == Approx(8.0).margin(0.5));
      CHECK(std::log2(e40 / e80) == Approx(8.0).margin(0.5));
    }
  }
}

TEST_CASE("OrbitPropagator steps backwards and ignores empty steps", "[sim][orbit]") {
  const KeplerOrbit kepler(OrbitElements{7000e3, 0.01, 98.0 * kDeg, 0.0, 0.0, 0.0});
  OrbitPropagator propagator(gravityOnly(true), UtcEpoch{}, kepler.at(0.0));
  const State s0 = propagator.state();
  propagator.step(0.0);
  propagator.step(std::nan(""));
  CHECK(propagator.time_s() == 0.0);
  CHECK((propagator.state().r_N_m - s0.r_N_m).norm() == 0.0);
  for (int i = 0; i < 10; ++i) propagator.step(30.0);
  for (int i = 0; i < 10; ++i) propagator.step(-30.0);
  CHECK(propagator.time_s() == 0.0);
  CHECK((propagator.state().r_N_m - s0.r_N_m).norm() < 1e-6);
}

TEST_CASE("OrbitPropagator rejects a bad set-up, naming every fault", "[sim][orbit]") {
  OrbitForceParams bad;
  bad.mass_kg = -1.0;
  UtcEpoch epoch;
  epoch.month = 13;
  const State inside{Eigen::Vector3d(1000e3, 0.0, 0.0), Eigen::Vector3d(0.0, 7000.0, 0.0)};
  try {
    OrbitPropagator propagator(bad, epoch, inside);
    FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    CHECK(what.find("mass_kg:") != std::string::npos);
    CHECK(what.find("epoch.month:") != std::string::npos);
    CHECK(what.find("initial.r_N_m:") != std::string::npos);
  }
}

TEST_CASE("J2 turns the node at the secular rate −3/2 n J2 (R/p)² cos i", "[sim][orbit]") {
  // Method: the osculating node, sampled every step over 15 whole revolutions, is
  // fitted by a straight line; the fit averages out the twice-per-revolution
  // short-period terms. The first-order closed form (Vallado ch. 9) is evaluated with the mean
  // (revolution-averaged) semi-major axis and inclination, so that the O(J2)
  // short-period offset of the initial osculating values does not enter.
  const OrbitElements elements{7000e3, 0.0, 50.0 * kDeg, 20.0 * kDeg, 0.0, 0.0};
  const KeplerOrbit kepler(elements);
  OrbitPropagator propagator(gravityOnly(true), UtcEpoch{}, kepler.at(0.0));
  const int per_revolution = 100;
  const double dt = kepler.period_s() / per_revolution;
  std::vector<double> t;
  std::vector<double> node;
  double sum_a = 0.0;
  double sum_i = 0.0;
  for (int k = 0; k < 15 * per_revolution; ++k) {
    t.push_back(propagator.time_s());
    node.push_back(raan(propagator.state()));
    sum_a += semiMajorAxis(propagator.state());
    sum_i += inclination(propagator.state());
    propagator.step(dt);
  }
  const double a = sum_a / t.size();
  const double i = sum_i / t.size();
  const double n = std::sqrt(kMu / (a * a * a));
  const double expected = -1.5 * n * kEgm2008J2 * std::pow(kEgm2008Radius_m / a, 2) * std::cos(i);
  const double measured = slope(t, node);
  INFO("measured " << measured << " rad/s, closed form " << expected << " rad/s");
  CHECK(measured == Approx(expected).epsilon(5e-3));
}

TEST_CASE("a sun-synchronous orbit keeps its node on the Sun for 30 days", "[sim][orbit]") {
  // 700 km circular; the SSO condition Ω̇ = 360°/365.2422 d fixes cos i from the
  // J2 secular rate. Epoch 28 January: the 30 days span the February extremum of the
  // equation of time, so the true Sun's uneven right ascension adds only ≈ 0.3°.
  const double a = kEarthEquatorialRadius_m + 700e3;
  const double n = std::sqrt(kMu / (a * a * a));
  const double node_rate = 2.0 * kPi / (365.2422 * 86400.0);
  const double cos_i = -node_rate / (1.5 * n * kEgm2008J2 * std::pow(kEgm2008Radius_m / a, 2));
  const UtcEpoch epoch{2026, 1, 28, 0, 0, 0.0};
  const double jd_tt0 = julianDate(epoch) + 69.184 / 86400.0;
  auto sunRightAscension = [&](double t_s) {
    const Eigen::Vector3d s = sunPosition_N_m(jd_tt0 + t_s / 86400.0);
    return std::atan2(s.y(), s.x());
  };
  const double ra0 = sunRightAscension(0.0);
  const KeplerOrbit kepler(OrbitElements{a, 0.0, std::acos(cos_i), ra0 + 90.0 * kDeg, 0.0, 0.0});
  OrbitPropagator propagator(gravityOnly(true), epoch, kepler.at(0.0));
  const double offset0 = raan(propagator.state()) - ra0;
  double worst = 0.0;
  for (int k = 0; k < 30 * 1440; ++k) {
    propagator.step(60.0);
    if (k % 60 != 0) continue;
    const double offset = raan(propagator.state()) - sunRightAscension(propagator.time_s());
    worst = std::max(worst, std::abs(std::remainder(offset - offset0, 2.0 * kPi)));
  }
  INFO("inclination " << std::acos(cos_i) / kDeg << "°, worst node − Sun drift " << worst / kDeg << "°");
  CHECK(std::acos(cos_i) / kDeg == Approx(98.19).margin(0.05));
  CHECK(worst < 0.5 * kDeg);
}
