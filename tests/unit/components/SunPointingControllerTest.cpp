// SPDX-License-Identifier: Apache-2.0
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "components/attitude_controller/SunPointingController.hpp"
#include "tests/support/TestUnits.hpp"

using flatsat::attitude_controller::SunPointingController;
using flatsat::attitude_controller::SunPointingControllerInput;
using flatsat::attitude_controller::SunPointingControllerParams;

namespace {

/// ROSAT-like pyramid: four wheels tilted by β from +x, in the xy and xz planes.
Eigen::Matrix<double, 3, 4> pyramidAxes(double beta) {
  const double c = std::cos(beta);
  const double s = std::sin(beta);
  Eigen::Matrix<double, 3, 4> A;
  A << c, c, c, c,  //
      s, -s, 0.0, 0.0,  //
      0.0, 0.0, s, -s;
  return A;
}

SunPointingControllerInput input(const Eigen::Vector3d& sun, const Eigen::Vector3d& w = Eigen::Vector3d::Zero(),
                                 const Eigen::Vector4d& speeds = Eigen::Vector4d::Zero()) {
  return {sun, w, speeds, true};
}

/// Default params with the slew-rate limit out of the way: the plain PD law.
SunPointingControllerParams pd() {
  SunPointingControllerParams p;
  p.max_rate_rad_s = 1e3;
  return p;
}

/// Rigid body with wheels, no external torque: J ω̇ = −ω × (Jω + A h) − A τ_m, ḣ = τ_m
/// (h: per-wheel momentum). RK4 for (ω, h), attitude by the exact rotation at the mean rate.
struct Plant {
  Eigen::Matrix3d J;
  Eigen::Matrix<double, 3, 4> A;
  Eigen::Quaterniond q_NB;
  Eigen::Vector3d w;
  Eigen::Vector4d h;

  Eigen::Vector3d wDot(const Eigen::Vector3d& w_, const Eigen::Vector4d& h_, const Eigen::Vector4d& tau_m) const {
    return J.ldlt().solve(-w_.cross(J * w_ + A * h_) - A * tau_m);
  }

  void step(const Eigen::Vector4d& tau_m, double dt) {
    const Eigen::Vector3d w0 = w;
    const Eigen::Vector3d k1 = wDot(w, h, tau_m);
    const Eigen::Vector3d k2 = wDot(w + 0.5 * dt * k1, h + 0.5 * dt * tau_m, tau_m);
    const Eigen::Vector3d k3 = wDot(w + 0.5 * dt * k2, h + 0.5 * dt * tau_m, tau_m);
    const Eigen::Vector3d k4 = wDot(w + dt * k3, h + dt * tau_m, tau_m);
    w += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    h += dt * tau_m;
    const Eigen::Vector3d w_mean = 0.5 * (w0 + w);
    const double n = w_mean.norm();
    if (n > 0.0) {
      q_NB = (q_NB * Eigen::Quaterniond(Eigen::AngleAxisd(n * dt, w_mean / n))).normalized();
    }
  }

  Eigen::Vector3d momentum_N() const { return q_NB * (J * w + A * h); }
};

}  // namespace

TEST_CASE("Sun pointing PD law: error vector, torque and wheel torques", "[components][attitude_controller]") {
  SunPointingControllerParams p = pd();
  p.kp_Nm_per_rad = 0.01;
  p.kd_Nm_s_per_rad = 0.5;
  p.max_torque_Nm = 0.05;
  SunPointingController ctl(p);
  GIVEN("the Sun on +y, the axis +x, at rest") {
    const auto out = ctl.step(input(Eigen::Vector3d::UnitY()), 0);
    THEN("e = 90° about +z, τ = kp·e, the x/y/z wheels spin up against it") {
      const Eigen::Vector3d tau(0.0, 0.0, 0.01 * kPi / 2.0);
      CHECK(out.pointing_error_rad == Approx(kPi / 2.0).epsilon(1e-14));
      CHECK((out.tau_cmd_B_Nm - tau).norm() < 1e-15);
      CHECK((out.wheel_torque_Nm - Eigen::Vector4d(0.0, 0.0, -tau.z(), 0.0)).norm() < 1e-15);
      CHECK_FALSE(out.saturated);
    }
  }
  GIVEN("the Sun 30° from +x towards +z, rotating at ω") {
    const Eigen::Vector3d w(0.001, -0.002, 0.003);
    const auto out = ctl.step(input(Eigen::Vector3d(std::cos(30 * kDeg), 0.0, std::sin(30 * kDeg)), w), 0);
    THEN("e = 30° about −y and τ = kp·e − kd·ω") {
      const Eigen::Vector3d tau = 0.01 * Eigen::Vector3d(0.0, -30 * kDeg, 0.0) - 0.5 * w;
      CHECK(out.pointing_error_rad == Approx(30 * kDeg).epsilon(1e-14));
      CHECK((out.tau_cmd_B_Nm - tau).norm() < 1e-15);
    }
  }
}

TEST_CASE("Sun pointing cancels the gyroscopic torque of the wheels", "[components][attitude_controller]") {
  SunPointingControllerParams p = pd();
  p.max_torque_Nm = 1.0;
  p.wheels.inertia_kg_m2 = Eigen::Vector4d(0.1, 0.2, 0.05, 0.3);
  SunPointingController ctl(p);
  const Eigen::Vector3d w(0.01, -0.02, 0.03);
  // h_w = Σ a_i I_i Ω_i with a = x, y, z; the unused fourth slot is ignored: (0.1, 0.2, −0.05).
  const auto out = ctl.step(input(Eigen::Vector3d::UnitX(), w, Eigen::Vector4d(1.0, 1.0, -1.0, 50.0)), 0);
  // Error zero: −k_d·ω plus ω × h = (−0.02·−0.05 − 0.03·0.2, 0.03·0.1 − 0.01·−0.05, 0.01·0.2 + 0.02·0.1).
  const Eigen::Vector3d tau = -p.kd_Nm_s_per_rad * w + Eigen::Vector3d(-0.005, 0.0035, 0.004);
  CHECK((out.tau_cmd_B_Nm - tau).norm() < 1e-16);
  CHECK(out.pointing_error_rad == 0.0);
}

TEST_CASE("Sun pointing limits the slew rate it commands", "[components][attitude_controller]") {
  SunPointingControllerParams p;
  p.kp_Nm_per_rad = 0.01;
  p.kd_Nm_s_per_rad = 0.5;
  p.max_rate_rad_s = 0.01;  // reached at |e| = 0.01·0.5/0.01 = 0.5 rad
  p.max_torque_Nm = 1.0;
  SunPointingController ctl(p);
  GIVEN("a 90° error about +z") {
    const Eigen::Vector3d sun = Eigen::Vector3d::UnitY();
    THEN("at rest the P term acts as if the error were 0.5 rad") {
      const auto out = ctl.step(input(sun), 0);
      CHECK(out.rate_limited);
      CHECK(out.pointing_error_rad == Approx(std::numbers::pi / 2.0).epsilon(1e-14));
      CHECK((out.tau_cmd_B_Nm - Eigen::Vector3d(0.0, 0.0, 0.005)).norm() < 1e-16);
    }
    THEN("slewing at max_rate about the error axis needs no torque") {
      CHECK(ctl.step(input(sun, Eigen::Vector3d(0.0, 0.0, 0.01)), 0).tau_cmd_B_Nm.norm() < 1e-17);
    }
  }
  GIVEN("an error below 0.5 rad") {
    const auto out = ctl.step(input(Eigen::Vector3d(std::cos(0.4), std::sin(0.4), 0.0)), 0);
    THEN("the plain PD law applies") {
      CHECK_FALSE(out.rate_limited);
      CHECK((out.tau_cmd_B_Nm - Eigen::Vector3d(0.0, 0.0, 0.01 * 0.4)).norm() < 1e-16);
    }
  }
}

TEST_CASE("Sun pointing saturates the torque keeping its direction", "[components][attitude_controller]") {
  SunPointingControllerParams p = pd();
  p.kp_Nm_per_rad = 1.0;
  p.kd_Nm_s_per_rad = 1.0;
  p.max_torque_Nm = 0.02;
  SunPointingController ctl(p);
  const Eigen::Vector3d w(0.01, 0.02, 0.0);
  const auto out = ctl.step(input(Eigen::Vector3d::UnitY(), w), 0);
  const Eigen::Vector3d raw = Eigen::Vector3d(0.0, 0.0, kPi / 2.0) - w;
  CHECK(out.saturated);
  CHECK(out.tau_cmd_B_Nm.norm() == Approx(0.02).epsilon(1e-14));
  CHECK((out.tau_cmd_B_Nm - 0.02 * raw.normalized()).norm() < 1e-15);
}

TEST_CASE("Sun pointing handles the Sun exactly behind the axis", "[components][attitude_controller]") {
  SunPointingControllerParams p = pd();
  p.kp_Nm_per_rad = 0.001;
  SunPointingController ctl(p);
  const auto out = ctl.step(input(-Eigen::Vector3d::UnitX()), 0);
  CHECK(out.pointing_error_rad == Approx(kPi).epsilon(1e-15));
  CHECK(out.tau_cmd_B_Nm.allFinite());
  CHECK(out.tau_cmd_B_Nm.norm() == Approx(0.001 * kPi).epsilon(1e-14));
  CHECK(std::abs(out.tau_cmd_B_Nm.x()) < 1e-18);  // a 180° turn about an axis normal to +x
}

TEST_CASE("Sun pointing commands nothing without a valid estimate", "[components][attitude_controller]") {
  SunPointingController ctl(SunPointingControllerParams{});
  auto in = input(Eigen::Vector3d::UnitY(), Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector4d(100.0, 0.0, 0.0, 0.0));
  in.valid = false;
  const auto out = ctl.step(in, 0);
  CHECK(out.tau_cmd_B_Nm == Eigen::Vector3d::Zero());
  CHECK(out.wheel_torque_Nm == Eigen::Vector4d::Zero());
  CHECK_FALSE(out.saturated);
  CHECK(ctl.step(input(Eigen::Vector3d::Zero()), 0).tau_cmd_B_Nm == Eigen::Vector3d::Zero());
}

TEST_CASE("Sun pointing distributes the torque over the wheels", "[components][attitude_controller]") {
  GIVEN("a four-wheel pyramid") {
    SunPointingControllerParams p = pd();
    p.max_torque_Nm = 0.1;
    p.wheels.count = 4;
    p.wheels.axes_B = pyramidAxes(60 * kDeg);
    SunPointingController ctl(p);
    const Eigen::Vector3d sun = Eigen::Vector3d(0.5, -0.6, 0.3).normalized();
    const Eigen::Vector3d w(1e-3, -2e-3, 0.0);
    const auto out = ctl.step(input(sun, w), 0);
    THEN("the body gets τ = kp·e − kd·ω from the minimum-norm motor torques") {
      const Eigen::Vector3d c = Eigen::Vector3d::UnitX().cross(sun);
      const Eigen::Vector3d e = std::atan2(c.norm(), sun.x()) * c.normalized();
      const Eigen::Vector3d tau = p.kp_Nm_per_rad * e - p.kd_Nm_s_per_rad * w;
      CHECK((-p.wheels.axes_B * out.wheel_torque_Nm - tau).norm() < 1e-15);
      CHECK((out.tau_cmd_B_Nm - tau).norm() < 1e-15);
      CHECK(std::abs(out.wheel_torque_Nm.dot(Eigen::Vector4d(1.0, 1.0, -1.0, -1.0))) < 1e-15);  // ⊥ null space
    }
  }
  GIVEN("only an x and a y wheel left") {
    SunPointingControllerParams p = pd();
    p.wheels.count = 2;
    SunPointingController ctl(p);
    p.wheels.count = 3;
    SunPointingController full(p);
    const auto in = input(Eigen::Vector3d(0.5, -0.6, 0.3).normalized(), Eigen::Vector3d(1e-3, 2e-3, 3e-3));
    const Eigen::Vector3d wanted = full.step(in, 0).tau_cmd_B_Nm;
    const auto out = ctl.step(in, 0);
    THEN("the output is the achievable part of the torque: its z part is lost") {
      CHECK((out.tau_cmd_B_Nm - Eigen::Vector3d(wanted.x(), wanted.y(), 0.0)).norm() < 1e-16);
      CHECK(out.wheel_torque_Nm[2] == 0.0);
    }
  }
}

TEST_CASE("Sun pointing converges to 0.1 deg in closed loop", "[components][attitude_controller]") {
  SunPointingControllerParams p;
  p.kp_Nm_per_rad = 0.05;
  p.kd_Nm_s_per_rad = 1.0;  // ζ ≈ 0.7 for J ≈ 10 kg·m²
  p.max_torque_Nm = 0.02;
  p.max_rate_rad_s = 0.02;
  p.wheels.count = 4;
  p.wheels.axes_B = pyramidAxes(60 * kDeg);
  p.wheels.inertia_kg_m2 = Eigen::Vector4d::Constant(0.05);
  SunPointingController ctl(p);

  Plant plant;
  plant.J << 12.0, 0.3, -0.2,  //
      0.3, 10.0, 0.1,          //
      -0.2, 0.1, 8.0;
  plant.A = p.wheels.axes_B;
  plant.q_NB = Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d(0.2, 1.0, -0.4).normalized()));
  plant.w = Eigen::Vector3d(0.01, -0.02, 0.015);
  plant.h = Eigen::Vector4d(0.05, -0.03, 0.02, 0.01);
  const Eigen::Vector3d sun_N = Eigen::Vector3d(1.0, 2.0, -0.5).normalized();
  const Eigen::Vector3d H0_N = plant.momentum_N();

  double worst_late_error = 0.0;
  double fastest_slew = 0.0;
  bool saturated = false;
  bool rate_limited = false;
  constexpr int kSteps = 9000;  // 900 s at 10 Hz
  for (int k = 0; k < kSteps; ++k) {
    const Eigen::Vector3d sun_B = plant.q_NB.conjugate() * sun_N;
    const Eigen::Vector4d speeds = plant.h.cwiseQuotient(p.wheels.inertia_kg_m2);
    const auto out = ctl.step(input(sun_B, plant.w, speeds), k * 100'000'000LL);
    saturated = saturated || out.saturated;
    rate_limited = rate_limited || out.rate_limited;
    if (k >= 600) {  // once the initial tumble is taken out
      fastest_slew = std::max(fastest_slew, plant.w.norm());
    }
    if (k >= kSteps - 1000) {
      const double error = std::atan2(sun_B.cross(Eigen::Vector3d::UnitX()).norm(), sun_B.x());
      worst_late_error = std::max(worst_late_error, error);
    }
    for (int sub = 0; sub < 10; ++sub) {
      plant.step(out.wheel_torque_Nm, 0.01);
    }
  }
  REQUIRE((plant.momentum_N() - H0_N).norm() < 1e-6 * H0_N.norm());  // the plant itself is sound
  CHECK(saturated);     // the large initial error exercised the torque limiter
  CHECK(rate_limited);  // and the slew-rate limit
  CHECK(fastest_slew < 1.05 * p.max_rate_rad_s);
  CHECK(worst_late_error < 0.1 * kDeg);
  CHECK(plant.w.norm() < 1e-4);
}

TEST_CASE("Sun pointing params reject bad values", "[components][attitude_controller]") {
  CHECK(SunPointingControllerParams{}.validate().empty());
  SunPointingControllerParams p;
  p.kp_Nm_per_rad = 0.0;
  p.kd_Nm_s_per_rad = 0.0;
  p.max_torque_Nm = std::numeric_limits<double>::infinity();
  p.max_rate_rad_s = -1.0;
  p.pointing_axis_B = Eigen::Vector3d(0.0, 0.0, 2.0);
  p.wheels.axes_B.col(1) *= 0.5;
  p.wheels.inertia_kg_m2[2] = 0.0;
  const auto errors = p.validate();
  REQUIRE(errors.size() == 7);
  CHECK(errors[0].rfind("kp_Nm_per_rad:", 0) == 0);
  CHECK(errors[1].rfind("kd_Nm_s_per_rad:", 0) == 0);
  CHECK(errors[2].rfind("max_torque_Nm:", 0) == 0);
  CHECK(errors[3].rfind("max_rate_rad_s:", 0) == 0);
  CHECK(errors[4].rfind("pointing_axis_B:", 0) == 0);
  CHECK(errors[5] == "wheels.axes_B: column 1 must be a unit vector");
  CHECK(errors[6] == "wheels.inertia_kg_m2: wheel 2 must be finite and > 0");
  p = SunPointingControllerParams{};
  p.wheels.count = 5;
  CHECK(p.validate() == std::vector<std::string>{"wheels.count: must be in 1..4"});
  CHECK_THROWS_AS(SunPointingController(p), std::invalid_argument);
}
