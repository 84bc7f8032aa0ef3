// SPDX-License-Identifier: Apache-2.0
// DynamicsModel with its disturbances and actuators: panels (drag,
// solar pressure), residual dipole, wheel friction, thrusters and S2 flaps.
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <catch2/catch.hpp>

#include "sim/Attitude.hpp"
#include "sim/Constants.hpp"
#include "sim/DynamicsModel.hpp"
#include "sim/SunEphemeris.hpp"
#include "tests/support/TestUnits.hpp"
#include "tests/unit/sim/PyramidWheels.hpp"

using namespace flatsat::sim;

namespace {

using test::kStep;

// A 560 km sun-synchronous small satellite: a 0.6 m box of six panels with the
// centre of mass off its centroid, a two-sided +y solar wing, a residual
// dipole, four wheels with friction, four thrusters (one gimballed), S2 flaps.
DynamicsParams fullyEquipped() {
  DynamicsParams p;
  p.epoch = UtcEpoch{2026, 6, 21, 12, 0, 0.0};
  p.orbit = OrbitElements{kEarthEquatorialRadius_m + 560e3, 0.001, 97.6 * kDeg, 30.0 * kDeg, 0.0, 0.0};
  p.body.J_B_kg_m2 = Eigen::Vector3d(2.0, 2.5, 3.0).asDiagonal();
  test::fitPyramidWheels(p.body);
  p.body.wheel_viscous_friction_Nms_rad.setConstant(2e-6);
  p.body.wheel_coulomb_friction_Nm.setConstant(5e-5);
  p.field = DipoleCoefficients{-29318.5, -1385.3, 4491.75};
  p.torquer_max_dipole_Am2 = Eigen::Vector3d::Constant(0.2);
  p.residual_dipole_B_Am2 = Eigen::Vector3d(0.02, -0.01, 0.03);
  p.density_kg_m3 = 2e-12;
  p.q0_NB = quatFromRotationVector(Eigen::Vector3d(0.3, -0.4, 1.2));
  p.w0_NB_B_rad_s = Eigen::Vector3d(0.01, -0.02, 0.015);
  p.wheel_speed0_rad_s = Eigen::Vector4d(50.0, -50.0, 30.0, -20.0);
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      Panel face;
      face.area_m2 = 0.36;
      face.normal_B = sign * Eigen::Vector3d::Unit(axis);
      face.r_cp_B_m = 0.3 * face.normal_B + Eigen::Vector3d(0.01, -0.02, 0.015);
      face.specular = 0.2;
      face.diffuse = 0.3;
      face.absorbed = 0.5;
      face.aero_specular = 0.1;
      p.panels.push_back(face);
    }
  }
  for (const double sign : {1.0, -1.0}) {
    Panel wing;
    wing.area_m2 = 0.8;
    wing.normal_B = sign * Eigen::Vector3d::UnitZ();
    wing.r_cp_B_m = Eigen::Vector3d(0.0, 1.0, 0.0);
    wing.specular = 0.05;
    wing.diffuse = 0.05;
    wing.absorbed = 0.9;
    p.panels.push_back(wing);
  }
  const auto thruster = [](const Eigen::Vector3d& r, const Eigen::Vector3d& d) {
    ThrusterParams t;
    t.r_B_m = r;
    t.direction_B = d;
    t.thrust_N = 0.05;
    t.min_impulse_bit_Ns = 5e-4;  // t_min = 10 ms
    return t;
  };
  p.thrusters = {thruster({0.0, 0.3, 0.0}, {0.0, 0.0, 1.0}), thruster({0.0, -0.3, 0.0}, {0.0, 0.0, -1.0}),
                 thruster({0.3, 0.0, 0.0}, {0.0, 1.0, 0.0}), thruster({0.0, 0.0, -0.3}, {0.0, 0.0, 1.0})};
  p.thrusters[3].gimballed = true;
  p.thrusters[3].gimbal_axis1_B = Eigen::Vector3d::UnitX();
  p.thrusters[3].gimbal_axis2_B = Eigen::Vector3d::UnitY();
  p.thrusters[3].gimbal_min_rad = Eigen::Vector2d::Constant(-0.1);
  p.thrusters[3].gimbal_max_rad = Eigen::Vector2d::Constant(0.1);
  p.flaps.fitted = true;
  p.flaps.plate_area_m2 = 0.1;
  p.flaps.lever_arm_m = 0.8;
  p.flaps.max_angle_rad = 1.0;
  return p;
}

// Air turning with the Earth, relative to the spacecraft, from the truth's own orbit state.
Eigen::Vector3d windFromTruth(const Truth& truth) {
  const Eigen::Vector3d air_N = kEarthRotationRate_rad_s * Eigen::Vector3d::UnitZ().cross(truth.r_N_m);
  return truth.q_NB.conjugate() * (air_N - truth.v_N_m_s);
}

}  // namespace

TEST_CASE("DynamicsParams::validate checks panels, thrusters, flaps and the environment", "[sim][disturbances]") {
  CHECK(DynamicsParams{}.panels.empty());
  CHECK(fullyEquipped().validate().empty());
  DynamicsParams p = fullyEquipped();
  p.panels[2].area_m2 = 0.0;
  p.thrusters[1].thrust_N = -1.0;
  p.flaps.lever_arm_m = 0.0;
  p.density_kg_m3 = -1e-12;
  p.residual_dipole_B_Am2.x() = std::numeric_limits<double>::quiet_NaN();
  p.body.wheel_coulomb_friction_Nm(0) = -1.0;
  const auto errors = p.validate();
  CHECK(errors.size() == 6);
  CHECK(anyStartsWith(errors, "panels[2].area_m2: "));
  CHECK(anyStartsWith(errors, "thrusters[1].thrust_N: "));
  CHECK(anyStartsWith(errors, "flaps.lever_arm_m: "));
  CHECK(anyStartsWith(errors, "density_kg_m3: "));
  CHECK(anyStartsWith(errors, "residual_dipole_B_Am2: "));
  CHECK(anyStartsWith(errors, "body.wheel_coulomb_friction_Nm[0]: "));

  DynamicsParams crowded = fullyEquipped();
  crowded.thrusters.resize(kMaxThrusters + 1, crowded.thrusters[0]);
  CHECK(crowded.validate() == std::vector<std::string>{"thrusters: 13 thrusters, at most 12"});
}

TEST_CASE("DynamicsModel applies drag, solar pressure and the residual dipole", "[sim][disturbances]") {
  DynamicsParams p = fullyEquipped();
  p.thrusters.clear();
  p.flaps.fitted = false;
  DynamicsModel model(p);
  const Truth before = model.truth();
  model.step(ActuatorCommands{}, kStep);
  const Truth& t = model.truth();

  THEN("wind and flux are those of the truth's own orbit, Sun and shadow") {
    CHECK((t.wind_B_m_s - windFromTruth(t)).norm() < 1e-9);
    // At the ascending node of a 97.6° orbit the air's 0.51 km/s eastward motion
    // adds to the satellite's 1.0 km/s westward component: |w| ≈ √(1.51² + 7.51²).
    CHECK(t.wind_B_m_s.norm() == Approx(7.66e3).epsilon(0.01));
    const double jd_tt = julianDate(p.epoch) + (toSeconds(t.t) + kTtMinusUtc_s) / 86400.0;
    const double distance = (sunPosition_N_m(jd_tt) - t.r_N_m).norm();
    REQUIRE(t.illumination == 1.0);
    CHECK(t.solar_flux_W_m2 == Approx(1361.0 * std::pow(kAstronomicalUnit_m / distance, 2)).epsilon(1e-12));
    CHECK(t.solar_flux_W_m2 == Approx(1316.0).epsilon(0.01));  // near aphelion
  }
  THEN("the torques are the panel model's and m_res × b_B") {
    const ForceTorque aero = aerodynamicForceTorque(p.panels, p.density_kg_m3, t.wind_B_m_s);
    const ForceTorque srp = solarPressureForceTorque(p.panels, t.sun_B_unit, t.solar_flux_W_m2);
    CHECK((t.tau_aerodynamic_B_Nm - aero.torque_B_Nm).norm() < 1e-22);
    CHECK((t.f_aerodynamic_B_N - aero.force_B_N).norm() < 1e-20);
    CHECK((t.tau_solar_pressure_B_Nm - srp.torque_B_Nm).norm() < 1e-22);
    CHECK((t.f_solar_pressure_B_N - srp.force_B_N).norm() < 1e-20);
    CHECK((t.tau_residual_magnetic_B_Nm - p.residual_dipole_B_Am2.cross(t.b_B_T)).norm() < 1e-22);
    CHECK(t.tau_aerodynamic_B_Nm.norm() > 1e-7);
    CHECK(t.tau_solar_pressure_B_Nm.norm() > 1e-8);
    CHECK(t.tau_flaps_B_Nm.isZero());
  }
  THEN("the momentum change is the total torque integrated over the step (trapezoid)") {
    const auto tau_N = [](const Truth& s) {
      return s.q_NB * (s.tau_gravity_gradient_B_Nm + s.tau_residual_magnetic_B_Nm + s.tau_aerodynamic_B_Nm +
                       s.tau_solar_pressure_B_Nm);
    };
    const Eigen::Vector3d expected = 0.5 * (tau_N(before) + tau_N(t)) * toSeconds(kStep);
    CHECK((t.H_total_N_Nms - before.H_total_N_Nms - expected).norm() < 1e-4 * expected.norm());
  }
}

TEST_CASE("DynamicsModel fires thrusters and moves the flaps", "[sim][actuators]") {
  DynamicsParams p = fullyEquipped();
  p.panels.clear();
  p.residual_dipole_B_Am2.setZero();
  p.gravity_gradient = false;
  DynamicsModel model(p);
  const Truth before = model.truth();
  ActuatorCommands cmd;
  cmd.thruster_on_time_s.head<4>() << 0.045, 0.0, 0.005, 0.1;  // 45 ms → 40 ms; 5 ms < t_min → nothing
  cmd.thruster_gimbal_rad.col(3) << 0.05, 0.3;                   // inner angle beyond its 0.1 rad limit
  cmd.flap_angle_rad << 0.3, -2.0, 0.0, 0.5;                      // θ2 beyond the 1 rad limit
  model.step(cmd, kStep);
  const Truth& t = model.truth();

  THEN("the truth reports what Thrusters delivers for the held command") {
    const ThrusterOutput out = Thrusters(p.thrusters).fire(cmd.thruster_on_time_s, cmd.thruster_gimbal_rad, 0.1);
    CHECK(t.thruster_impulse_Ns.head<4>().isApprox(Eigen::Vector4d(0.05 * 0.04, 0.0, 0.0, 0.05 * 0.1), 1e-12));
    CHECK(t.thruster_gimbal_applied_rad.col(3) == Eigen::Vector2d(0.05, 0.1));
    CHECK(t.tau_thruster_B_Nm == out.torque_B_Nm);
    CHECK(t.f_thruster_B_N == out.force_B_N);
  }
  THEN("the flaps sit at the limited angles and their drag torque is the panel model's") {
    CHECK(t.flap_angle_applied_rad == Eigen::Vector4d(0.3, -1.0, 0.0, 0.5));
    const auto faces = Flaps(p.flaps).panels(t.flap_angle_applied_rad);
    const ForceTorque aero = aerodynamicForceTorque(faces, p.density_kg_m3, t.wind_B_m_s);
    CHECK((t.tau_flaps_B_Nm - aero.torque_B_Nm).norm() < 1e-22);
    CHECK(t.tau_aerodynamic_B_Nm == t.tau_flaps_B_Nm);  // no body panels
    CHECK(t.tau_flaps_B_Nm.norm() > 1e-8);
  }
  THEN("the momentum change is the thrusters' angular impulse plus the small flap torques") {
    // Both are held in the body over the step (the flaps left neutral at t = 0
    // only from the step's start), so the end values stand for the whole step.
    const Eigen::Vector3d tau_B = t.tau_thruster_B_Nm + t.tau_aerodynamic_B_Nm + t.tau_solar_pressure_B_Nm;
    const Eigen::Vector3d expected = 0.5 * (before.q_NB * tau_B + t.q_NB * tau_B) * 0.1;
    CHECK((t.H_total_N_Nms - before.H_total_N_Nms - expected).norm() < 1e-5 * expected.norm());
  }
}

TEST_CASE("DynamicsModel: wheel friction is internal and reported", "[sim][actuators]") {
  DynamicsParams p = fullyEquipped();
  p.panels.clear();
  p.thrusters.clear();
  p.flaps.fitted = false;
  p.residual_dipole_B_Am2.setZero();
  p.gravity_gradient = false;
  DynamicsModel model(p);
  const Truth start = model.truth();
  for (int k = 1; k <= 1000; ++k) model.step(ActuatorCommands{}, k * kStep);
  const Truth& t = model.truth();
  THEN("H_N is conserved while every coasting wheel slows down") {
    CHECK((t.H_total_N_Nms - start.H_total_N_Nms).norm() < 1e-10 * start.H_total_N_Nms.norm());
    for (int i = 0; i < 4; ++i) CHECK(std::abs(t.wheel_speed_rad_s(i)) < std::abs(start.wheel_speed_rad_s(i)));
  }
  THEN("the reported friction is −c_v Ω − c_c sgn Ω (all speeds far outside the stiction band)") {
    const Eigen::Vector4d expected = -2e-6 * t.wheel_speed_rad_s - 5e-5 * t.wheel_speed_rad_s.cwiseSign();
    CHECK((t.wheel_friction_torque_Nm - expected).norm() < 1e-18);
  }
}

TEST_CASE("DynamicsModel with every model fitted is deterministic", "[sim][actuators]") {
  const auto command = [](int k) {
    ActuatorCommands cmd;
    cmd.wheel_torque_Nm = 0.02 * Eigen::Vector4d(std::sin(0.01 * k), std::cos(0.013 * k), -0.2, 0.3);
    cmd.dipole_B_Am2 = 0.3 * Eigen::Vector3d(std::cos(0.002 * k), std::sin(0.003 * k), -0.5);
    cmd.thruster_on_time_s.head<4>() = 0.1 * Eigen::Vector4d(std::sin(0.05 * k), std::cos(0.03 * k), 0.3, 0.7);
    cmd.thruster_gimbal_rad.col(3) << 0.2 * std::sin(0.01 * k), -0.05;
    cmd.flap_angle_rad = Eigen::Vector4d(std::sin(0.004 * k), 0.3, -1.5, 0.001 * k);
    return cmd;
  };
  DynamicsModel first(fullyEquipped());
  DynamicsModel second(fullyEquipped());
  for (int k = 1; k <= 500; ++k) {
    first.step(command(k), k * kStep);
    second.step(command(k), k * kStep);
  }
  const Truth& a = first.truth();
  const Truth& b = second.truth();
  const auto same = [](const auto& x, const auto& y) {
    return std::memcmp(x.data(), y.data(), sizeof(double) * x.size()) == 0;
  };
  CHECK(same(a.q_NB.coeffs(), b.q_NB.coeffs()));
  CHECK(same(a.w_NB_B_rad_s, b.w_NB_B_rad_s));
  CHECK(same(a.wheel_speed_rad_s, b.wheel_speed_rad_s));
  CHECK(same(a.tau_aerodynamic_B_Nm, b.tau_aerodynamic_B_Nm));
  CHECK(same(a.tau_solar_pressure_B_Nm, b.tau_solar_pressure_B_Nm));
  CHECK(same(a.thruster_impulse_Ns, b.thruster_impulse_Ns));
  CHECK(same(a.wheel_friction_torque_Nm, b.wheel_friction_torque_Nm));
}

TEST_CASE("DynamicsModel: a quiet part of the step switches the coils off", "[sim][actuators]") {
  // Duty-cycling against magnetometer sampling: coils on over the
  // first (1 - q) of the step only. The coils' share of the momentum change is
  // then (1 - q) times that of a full step, to the field's and attitude's
  // change within 0.1 s.
  DynamicsParams p = fullyEquipped();
  p.thrusters.clear();
  p.flaps.fitted = false;
  const auto momentumChange = [&](const Eigen::Vector3d& m, double quiet, Eigen::Vector3d* at_end = nullptr) {
    DynamicsModel model(p);
    const Eigen::Vector3d h0 = model.truth().H_total_N_Nms;
    ActuatorCommands cmd;
    cmd.dipole_B_Am2 = m;
    cmd.dipole_quiet_fraction = quiet;
    model.step(cmd, kStep);
    if (at_end != nullptr) *at_end = model.truth().dipole_at_t_B_Am2;
    return Eigen::Vector3d(model.truth().H_total_N_Nms - h0);
  };
  const Eigen::Vector3d m(0.15, -0.1, 0.12);
  const Eigen::Vector3d none = momentumChange(Eigen::Vector3d::Zero(), 0.0);
  Eigen::Vector3d dipole_at_end;
  const Eigen::Vector3d full = momentumChange(m, 0.0, &dipole_at_end) - none;
  CHECK((dipole_at_end - m).norm() < 1e-15);
  for (const double quiet : {0.25, 0.5, 0.9}) {
    const Eigen::Vector3d part = momentumChange(m, quiet, &dipole_at_end) - none;
    INFO("quiet fraction " << quiet);
    CHECK((part - (1.0 - quiet) * full).norm() < 1e-3 * full.norm());
    CHECK(dipole_at_end.isZero());  // what a magnetometer sampling at the step's end sees
  }
  CHECK((momentumChange(m, 1.5) - none - full).norm() < 1e-12 * full.norm());  // out of [0, 1): ignored
}
