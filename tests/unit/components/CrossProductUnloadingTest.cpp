// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "components/unloading_controller/CrossProductUnloading.hpp"

using flatsat::unloading_controller::CrossProductUnloading;
using flatsat::unloading_controller::CrossProductUnloadingInput;
using flatsat::unloading_controller::CrossProductUnloadingParams;

namespace {

constexpr double kInertia_kg_m2 = 1e-4;  // default rotor inertia

/// Default params (x, y, z wheels) with coils large enough never to saturate.
CrossProductUnloadingParams unsaturated() {
  CrossProductUnloadingParams p;
  p.max_dipole_Am2 = Eigen::Vector3d::Constant(1e6);
  return p;
}

/// Tachometer input giving body momentum h on the default x, y, z wheels.
CrossProductUnloadingInput withMomentum(const Eigen::Vector3d& h, const Eigen::Vector3d& b) {
  Eigen::Vector4d speeds = Eigen::Vector4d::Zero();
  speeds.head<3>() = h / kInertia_kg_m2;
  return {speeds, b, true};
}

}  // namespace

TEST_CASE("Unloading torque is -k times the momentum normal to the field", "[components][unloading_controller]") {
  CrossProductUnloading law(unsaturated());
  const double k = CrossProductUnloadingParams{}.gain_per_s;
  const Eigen::Vector3d cases[][2] = {
      {{0.02, -0.01, 0.005}, {2.1e-5, -3.4e-5, 1.7e-5}},
      {{-0.1, 0.0, 0.0}, {0.0, 3e-5, 0.0}},   // H ⊥ B: all of it dumps
      {{0.0, 0.04, 0.0}, {0.0, -2e-5, 0.0}},  // H ∥ B: nothing can dump
      {{0.03, 0.03, -0.06}, {-4e-5, 1e-5, 2e-5}},
  };
  for (const auto& [h, b] : cases) {
    const auto out = law.step(withMomentum(h, b), 0);
    const Eigen::Vector3d b_hat = b.normalized();
    const Eigen::Vector3d h_perp = h - b_hat * b_hat.dot(h);
    CHECK((out.h_B_Nms - h).norm() < 1e-15);
    CHECK((out.h_perp_B_Nms - h_perp).norm() < 1e-15);
    CHECK((out.m_B_Am2.cross(b) + k * h_perp).norm() < 1e-12 * h.norm());
    CHECK(std::abs(out.m_B_Am2.dot(b)) < 1e-12 * out.m_B_Am2.norm() * b.norm() + 1e-30);  // a dipole ∥ B is wasted
    CHECK(out.active);
    CHECK_FALSE(out.saturated);
  }
}

TEST_CASE("Unloading reads H from the tachometers of a skewed wheel set", "[components][unloading_controller]") {
  CrossProductUnloadingParams p = unsaturated();
  const double s = 1.0 / std::sqrt(3.0);
  p.wheels.count = 3;
  p.wheels.axes_B << 1.0, 0.0, s, 0.7,  //
      0.0, 1.0, s, 0.7,                //
      0.0, 0.0, s, 0.7;                // slot 3 is not a unit vector: unused, never read
  p.wheels.inertia_kg_m2 = Eigen::Vector4d(1e-4, 2e-4, 3e-4, 0.0);
  p.h_target_B_Nms = Eigen::Vector3d(0.0, 0.0, 0.01);
  CrossProductUnloading law(p);
  const auto out = law.step({Eigen::Vector4d(100.0, -50.0, 200.0, 1e6), Eigen::Vector3d(0, 0, 3e-5), true}, 0);
  // Σ a_i I_i Ω_i − h_target = (0.01, 0, 0) + (0, −0.01, 0) + 0.06·(s, s, s) − (0, 0, 0.01).
  const Eigen::Vector3d h(0.01 + 0.06 * s, -0.01 + 0.06 * s, 0.06 * s - 0.01);
  CHECK((out.h_B_Nms - h).norm() < 1e-15);
}

TEST_CASE("Unloading saturates the coils keeping the dipole direction", "[components][unloading_controller]") {
  CrossProductUnloadingParams p;
  p.max_dipole_Am2 = Eigen::Vector3d(0.2, 0.1, 0.3);
  CrossProductUnloading law(p);
  const Eigen::Vector3d h(0.05, -0.08, 0.02);
  const Eigen::Vector3d b(2e-5, 1e-5, -3e-5);
  const Eigen::Vector3d m_free = p.gain_per_s * h.cross(b) / b.squaredNorm();
  REQUIRE((m_free.cwiseAbs().array() > p.max_dipole_Am2.array()).any());
  const auto out = law.step(withMomentum(h, b), 0);
  CHECK(out.saturated);
  CHECK((out.m_B_Am2.cwiseAbs().array() <= p.max_dipole_Am2.array() * (1.0 + 1e-15)).all());
  // The tightest coil sits exactly at its limit.
  CHECK((out.m_B_Am2.cwiseAbs() - p.max_dipole_Am2).cwiseAbs().minCoeff() < 1e-15);
  CHECK(out.m_B_Am2.cross(m_free).norm() < 1e-12 * out.m_B_Am2.norm() * m_free.norm());
  CHECK(out.m_B_Am2.dot(m_free) > 0.0);
}

TEST_CASE("Unloading hysteresis starts above h_start and stops below h_stop", "[components][unloading_controller]") {
  CrossProductUnloadingParams p;
  p.h_start_Nms = 0.05;
  p.h_stop_Nms = 0.02;
  CrossProductUnloading law(p);
  const Eigen::Vector3d b(0.0, 0.0, 3e-5);
  const auto activeAt = [&](double h) { return law.step(withMomentum({h, 0.0, 0.0}, b), 0).active; };
  CHECK_FALSE(activeAt(0.03));  // between the thresholds, not yet started
  CHECK(activeAt(0.06));
  CHECK(activeAt(0.03));  // still draining
  CHECK_FALSE(activeAt(0.01));
  CHECK_FALSE(activeAt(0.03));
  CHECK(activeAt(0.06));
  law.reset();
  CHECK_FALSE(activeAt(0.03));
}

TEST_CASE("Unloading commands nothing when off or without a usable field", "[components][unloading_controller]") {
  const Eigen::Vector3d h(0.05, -0.08, 0.02);
  GIVEN("unloading disabled") {
    CrossProductUnloadingParams p;
    p.enabled = false;
    CrossProductUnloading law(p);
    const auto out = law.step(withMomentum(h, Eigen::Vector3d(2e-5, 1e-5, -3e-5)), 0);
    THEN("no dipole, but the momentum is still reported") {
      CHECK(out.m_B_Am2 == Eigen::Vector3d::Zero());
      CHECK_FALSE(out.active);
      CHECK((out.h_B_Nms - h).norm() < 1e-15);
    }
  }
  GIVEN("a field flagged invalid or weaker than min_field_T") {
    CrossProductUnloading law(CrossProductUnloadingParams{});  // min_field_T = 1 µT
    auto invalid = withMomentum(h, Eigen::Vector3d(2e-5, 1e-5, -3e-5));
    invalid.b_valid = false;
    for (const auto& in : {invalid, withMomentum(h, Eigen::Vector3d(5e-7, 0.0, 0.0))}) {
      const auto out = law.step(in, 0);
      CHECK(out.m_B_Am2 == Eigen::Vector3d::Zero());
      CHECK(out.h_perp_B_Nms == Eigen::Vector3d::Zero());
      CHECK_FALSE(out.active);
    }
  }
}

TEST_CASE("Unloading drains all momentum as the field turns over an orbit", "[components][unloading_controller]") {
  // The attitude loop holds the body, so the wheels absorb the magnetic torque: ḣ = m × B.
  // d|H|²/dt = −2k|H⊥|² ≤ 0; with B turning uniformly in the xz plane, H_y decays at k and,
  // for k well below the orbit rate, the in-plane part at k/2 on average.
  CrossProductUnloadingParams p = unsaturated();
  p.gain_per_s = 1e-4;
  CrossProductUnloading law(p);
  const double orbit_rate = 2.0 * std::numbers::pi / 5400.0;
  const double dt = 1.0;
  Eigen::Vector3d h(0.05, -0.08, 0.02);
  const double h0 = h.norm();
  double previous = h0;
  bool monotone = true;
  const double duration = 4.0 * 5400.0;
  for (double t = 0.0; t < duration; t += dt) {
    const Eigen::Vector3d b = 3e-5 * Eigen::Vector3d(std::cos(orbit_rate * t), 0.0, std::sin(orbit_rate * t));
    h += dt * law.step(withMomentum(h, b), 0).m_B_Am2.cross(b);
    monotone = monotone && h.norm() <= previous;
    previous = h.norm();
  }
  CHECK(monotone);
  // H_y is always ⊥ B: each Euler step scales it by exactly (1 − k·dt).
  CHECK(h.y() == Approx(-0.08 * std::pow(1.0 - p.gain_per_s * dt, duration / dt)).epsilon(1e-9));
  CHECK(h.norm() < 1.2 * h0 * std::exp(-0.5 * p.gain_per_s * duration));
}

TEST_CASE("Unloading params reject bad values", "[components][unloading_controller]") {
  CHECK(CrossProductUnloadingParams{}.validate().empty());
  CrossProductUnloadingParams p;
  p.gain_per_s = 0.0;
  p.max_dipole_Am2.z() = -0.1;
  p.wheels.axes_B.col(0) = Eigen::Vector3d(1.0, 1.0, 0.0);
  p.wheels.inertia_kg_m2[2] = 0.0;
  p.h_target_B_Nms.x() = std::numeric_limits<double>::infinity();
  p.h_stop_Nms = 0.05;
  p.h_start_Nms = 0.02;
  p.min_field_T = 0.0;
  const auto errors = p.validate();
  REQUIRE(errors.size() == 7);
  CHECK(errors[0].rfind("gain_per_s:", 0) == 0);
  CHECK(errors[1].rfind("max_dipole_Am2:", 0) == 0);
  CHECK(errors[2] == "wheels.axes_B: column 0 must be a unit vector");
  CHECK(errors[3] == "wheels.inertia_kg_m2: wheel 2 must be finite and > 0");
  CHECK(errors[4].rfind("h_target_B_Nms:", 0) == 0);
  CHECK(errors[5].rfind("h_start_Nms:", 0) == 0);
  CHECK(errors[6].rfind("min_field_T:", 0) == 0);
  CHECK_THROWS_AS(CrossProductUnloading(p), std::invalid_argument);
}
