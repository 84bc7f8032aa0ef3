// SPDX-License-Identifier: Apache-2.0
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "sim/Attitude.hpp"
#include "sim/Disturbances.hpp"
#include "sim/DynamicsModel.hpp"
#include "sim/SunEphemeris.hpp"
#include "tests/support/TestUnits.hpp"
#include "tests/unit/sim/PyramidWheels.hpp"

using namespace flatsat::sim;
using Catch::Matchers::Contains;

namespace {

using test::kStep;

DynamicsParams sunSynchronousSmallSat() {
  DynamicsParams p;
  p.epoch = UtcEpoch{2026, 3, 20, 12, 0, 0.0};
  p.orbit = OrbitElements{kEarthEquatorialRadius_m + 560e3, 0.001, 97.6 * kDeg, 30.0 * kDeg, 0.0, 0.0};
  p.body.J_B_kg_m2 << 2.0, 0.05, -0.03,  //
      0.05, 2.5, 0.02,                   //
      -0.03, 0.02, 3.0;
  test::fitPyramidWheels(p.body);
  p.field = DipoleCoefficients{-29318.5, -1385.3, 4491.75};
  p.torquer_max_dipole_Am2 = Eigen::Vector3d::Constant(0.2);
  p.gravity_gradient = false;
  p.q0_NB = quatFromRotationVector(Eigen::Vector3d(0.3, -0.4, 1.2));
  p.w0_NB_B_rad_s = Eigen::Vector3d(0.01, -0.02, 0.015);
  p.wheel_speed0_rad_s = Eigen::Vector4d(50.0, -50.0, 30.0, 0.0);
  return p;
}

bool sameBits(const Truth& a, const Truth& b) {
  const auto same = [](const auto& x, const auto& y) {
    return std::memcmp(x.data(), y.data(), sizeof(double) * x.size()) == 0;
  };
  return a.t == b.t && same(a.q_NB.coeffs(), b.q_NB.coeffs()) && same(a.w_NB_B_rad_s, b.w_NB_B_rad_s) &&
         same(a.wheel_speed_rad_s, b.wheel_speed_rad_s) && same(a.wheel_torque_applied_Nm, b.wheel_torque_applied_Nm) &&
         same(a.h_wheels_B_Nms, b.h_wheels_B_Nms) && same(a.H_total_N_Nms, b.H_total_N_Nms) && same(a.r_N_m, b.r_N_m) &&
         same(a.v_N_m_s, b.v_N_m_s) && same(a.b_N_T, b.b_N_T) && same(a.b_B_T, b.b_B_T) &&
         same(a.sun_N_unit, b.sun_N_unit) && same(a.sun_B_unit, b.sun_B_unit) &&
         std::memcmp(&a.illumination, &b.illumination, sizeof(double)) == 0 &&
         same(a.dipole_applied_B_Am2, b.dipole_applied_B_Am2) &&
         same(a.tau_gravity_gradient_B_Nm, b.tau_gravity_gradient_B_Nm) &&
         same(a.tau_magnetic_B_Nm, b.tau_magnetic_B_Nm) && same(a.tau_disturbance_B_Nm, b.tau_disturbance_B_Nm) &&
         same(a.tau_residual_magnetic_B_Nm, b.tau_residual_magnetic_B_Nm) &&
         same(a.wheel_friction_torque_Nm, b.wheel_friction_torque_Nm) && same(a.wind_B_m_s, b.wind_B_m_s) &&
         std::memcmp(&a.solar_flux_W_m2, &b.solar_flux_W_m2, sizeof(double)) == 0 &&
         same(a.f_aerodynamic_B_N, b.f_aerodynamic_B_N) && same(a.tau_aerodynamic_B_Nm, b.tau_aerodynamic_B_Nm) &&
         same(a.tau_flaps_B_Nm, b.tau_flaps_B_Nm) && same(a.f_solar_pressure_B_N, b.f_solar_pressure_B_N) &&
         same(a.tau_solar_pressure_B_Nm, b.tau_solar_pressure_B_Nm) &&
         same(a.flap_angle_applied_rad, b.flap_angle_applied_rad) && same(a.f_thruster_B_N, b.f_thruster_B_N) &&
         same(a.tau_thruster_B_Nm, b.tau_thruster_B_Nm) && same(a.thruster_impulse_Ns, b.thruster_impulse_Ns) &&
         same(a.thruster_gimbal_applied_rad, b.thruster_gimbal_applied_rad);
}

// A command sequence that exercises saturation of both actuators.
ActuatorCommands scriptedCommand(int k) {
  ActuatorCommands cmd;
  cmd.wheel_torque_Nm = 0.02 * Eigen::Vector4d(std::sin(0.01 * k), std::cos(0.013 * k), -std::sin(0.007 * k), 0.3);
  cmd.dipole_B_Am2 = 0.3 * Eigen::Vector3d(std::cos(0.002 * k), std::sin(0.003 * k), -0.5);
  return cmd;
}

}  // namespace

TEST_CASE("DynamicsParams::validate prefixes nested errors", "[sim][dynamics]") {
  CHECK(sunSynchronousSmallSat().validate().empty());

  DynamicsParams p = sunSynchronousSmallSat();
  p.epoch.month = 13;
  p.orbit.eccentricity = 1.5;
  p.body.wheel_inertia_kg_m2(2) = -1.0;
  p.substeps = 0;
  p.q0_NB.coeffs() *= 2.0;
  p.torquer_max_dipole_Am2.x() = -0.1;
  const auto errors = p.validate();
  const auto has = [&](const std::string& prefix) {
    return std::any_of(errors.begin(), errors.end(), [&](const std::string& e) { return e.rfind(prefix, 0) == 0; });
  };
  CHECK(has("epoch.month: 13"));
  CHECK(has("orbit.eccentricity: 1.5 must be in [0, 1)"));
  CHECK(has("body.wheel_inertia_kg_m2[2]: "));
  CHECK(has("substeps: 0"));
  CHECK(has("q0_NB: must be a unit quaternion"));
  CHECK(has("torquer_max_dipole_Am2: "));
  CHECK_THROWS_AS(DynamicsModel(p), std::invalid_argument);
  CHECK_THROWS_WITH(DynamicsModel(p), Contains("orbit.eccentricity") && Contains("substeps"));

  GIVEN("an initial wheel speed beyond the momentum limit") {
    DynamicsParams fast = sunSynchronousSmallSat();
    fast.wheel_speed0_rad_s(1) = -200.0;  // 0.4 N m s > 0.3
    CHECK(fast.validate().size() == 1);
    CHECK_THAT(fast.validate().front(), Contains("wheel_speed0_rad_s[1]"));
  }
}

TEST_CASE("DynamicsModel initial truth", "[sim][dynamics]") {
  const DynamicsParams p = sunSynchronousSmallSat();
  const DynamicsModel model(p);
  const Truth& truth = model.truth();
  CHECK(truth.t == 0);
  CHECK(truth.q_NB.isApprox(p.q0_NB, 1e-15));
  CHECK((truth.wheel_speed_rad_s - p.wheel_speed0_rad_s).norm() < 1e-12);
  CHECK((truth.r_N_m - KeplerOrbit(p.orbit).at(0.0).r_N_m).norm() < 1e-6);
  CHECK(truth.r_N_m.norm() == Approx(p.orbit.semi_major_axis_m * (1.0 - p.orbit.eccentricity)).epsilon(1e-12));
  CHECK(truth.wheel_torque_applied_Nm.isZero());
  CHECK(truth.dipole_applied_B_Am2.isZero());

  THEN("the field lies between the dipole-equator and dipole-pole magnitudes") {
    const double g = Eigen::Vector3d(p.field.g10_nT, p.field.g11_nT, p.field.h11_nT).norm() * 1e-9;
    const double scale = std::pow(kIgrfReferenceRadius_m / truth.r_N_m.norm(), 3);
    CHECK(truth.b_N_T.norm() >= g * scale * (1.0 - 1e-12));
    CHECK(truth.b_N_T.norm() <= 2.0 * g * scale * (1.0 + 1e-12));
    CHECK((truth.b_B_T - p.q0_NB.conjugate() * truth.b_N_T).norm() < 1e-20);
  }
  THEN("the Sun direction is a unit vector close to the Earth–Sun line") {
    const double jd_tt = julianDate(p.epoch) + kTtMinusUtc_s / 86400.0;
    CHECK(truth.sun_N_unit.norm() == Approx(1.0).epsilon(1e-15));
    CHECK(angleBetween(truth.sun_N_unit, sunPosition_N_m(jd_tt)) < 1e-4);  // parallax ≤ 7000 km / 1 AU
    CHECK((truth.sun_B_unit - p.q0_NB.conjugate() * truth.sun_N_unit).norm() < 1e-15);
    CHECK(truth.illumination >= 0.0);
    CHECK(truth.illumination <= 1.0);
  }
}

TEST_CASE("DynamicsModel conserves angular momentum without external torque", "[sim][dynamics]") {
  DynamicsModel model(sunSynchronousSmallSat());
  const Eigen::Vector3d H0 = model.truth().H_total_N_Nms;
  WHEN("no commands are given") {
    for (int k = 1; k <= 3000; ++k) model.step(ActuatorCommands{}, k * kStep);
    CHECK((model.truth().H_total_N_Nms - H0).norm() < 1e-10 * H0.norm());
    CHECK(model.truth().t == 3000 * kStep);
  }
  WHEN("only the wheels are commanded (internal torque)") {
    ActuatorCommands cmd;
    cmd.wheel_torque_Nm = Eigen::Vector4d(1e-4, -2e-4, 5e-5, 1e-4);  // stays inside the momentum limits
    for (int k = 1; k <= 3000; ++k) model.step(cmd, k * kStep);
    CHECK((model.truth().H_total_N_Nms - H0).norm() < 1e-10 * H0.norm());
    CHECK(model.truth().wheel_torque_applied_Nm == cmd.wheel_torque_Nm);
  }
}

TEST_CASE("DynamicsModel applies the magnetic torque m × b", "[sim][dynamics]") {
  DynamicsModel model(sunSynchronousSmallSat());
  ActuatorCommands cmd;
  cmd.dipole_B_Am2 = Eigen::Vector3d(0.1, -0.3, 0.05);  // y beyond the 0.2 A m² coil limit
  const Truth before = model.truth();
  const Eigen::Vector3d m_applied(0.1, -0.2, 0.05);
  model.step(cmd, kStep);
  const Truth& after = model.truth();

  THEN("the dipole is clipped per coil and the torque is m × b_B") {
    CHECK(after.dipole_applied_B_Am2 == m_applied);
    CHECK((after.tau_magnetic_B_Nm - m_applied.cross(after.b_B_T)).norm() < 1e-20);
  }
  THEN("the momentum change is the torque integrated over the step (trapezoid)") {
    const Eigen::Vector3d tau_N_start = before.q_NB * m_applied.cross(before.b_B_T);
    const Eigen::Vector3d tau_N_end = after.q_NB * after.tau_magnetic_B_Nm;
    const Eigen::Vector3d expected = 0.5 * (tau_N_start + tau_N_end) * toSeconds(kStep);
    CHECK((after.H_total_N_Nms - before.H_total_N_Nms - expected).norm() < 1e-4 * expected.norm());
  }
}

TEST_CASE("DynamicsModel saturates wheel commands and ignores steps back in time", "[sim][dynamics]") {
  DynamicsModel model(sunSynchronousSmallSat());
  ActuatorCommands cmd;
  cmd.wheel_torque_Nm = Eigen::Vector4d(1.0, -1.0, 0.005, std::nan(""));
  model.step(cmd, kStep);
  CHECK(model.truth().wheel_torque_applied_Nm == Eigen::Vector4d(0.01, -0.01, 0.005, 0.0));

  const Truth at_step = model.truth();
  model.step(cmd, kStep);
  model.step(cmd, 0);
  CHECK(sameBits(model.truth(), at_step));
}

TEST_CASE("DynamicsModel reports the gravity-gradient torque it applies", "[sim][dynamics]") {
  DynamicsParams p = sunSynchronousSmallSat();
  p.gravity_gradient = true;
  p.disturbance_torque_B_Nm = Eigen::Vector3d(1e-7, 0.0, -2e-7);
  DynamicsModel model(p);
  model.step(ActuatorCommands{}, kStep);
  const Truth& truth = model.truth();
  const Eigen::Vector3d r_B = truth.q_NB.conjugate() * truth.r_N_m;
  CHECK((truth.tau_gravity_gradient_B_Nm - gravityGradientTorque_B_Nm(r_B, p.body.J_B_kg_m2)).norm() < 1e-20);
  CHECK(truth.tau_gravity_gradient_B_Nm.norm() > 0.0);
  CHECK(truth.tau_disturbance_B_Nm == p.disturbance_torque_B_Nm);
}

TEST_CASE("DynamicsModel is deterministic", "[sim][dynamics]") {
  DynamicsParams p = sunSynchronousSmallSat();
  p.gravity_gradient = true;
  DynamicsModel first(p);
  DynamicsModel second(p);
  for (int k = 1; k <= 1000; ++k) {
    first.step(scriptedCommand(k), k * kStep);
    second.step(scriptedCommand(k), k * kStep);
  }
  THEN("same params and commands give bit-identical truth") { CHECK(sameBits(first.truth(), second.truth())); }

  WHEN("the first model is reset and run again") {
    const Truth end = first.truth();
    first.reset();
    CHECK(first.truth().t == 0);
    for (int k = 1; k <= 1000; ++k) first.step(scriptedCommand(k), k * kStep);
    CHECK(sameBits(first.truth(), end));
  }
}
