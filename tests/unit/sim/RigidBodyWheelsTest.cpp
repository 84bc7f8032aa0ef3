// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <limits>
#include <string>

#include <catch2/catch.hpp>

#include "sim/Attitude.hpp"
#include "sim/RigidBodyWheels.hpp"
#include "tests/support/TestUnits.hpp"
#include "tests/unit/sim/PyramidWheels.hpp"

using namespace flatsat::sim;
using Catch::Matchers::Contains;

namespace {

// Small satellite with a non-diagonal inertia and four wheels in a pyramid.
RigidBodyParams pyramidSpacecraft() {
  RigidBodyParams p;
  p.J_B_kg_m2 << 2.0, 0.05, -0.03,  //
      0.05, 2.5, 0.02,              //
      -0.03, 0.02, 3.0;
  test::fitPyramidWheels(p);
  return p;
}

RigidBodyParams withOneWheel(const Eigen::Vector3d& axis, double inertia) {
  RigidBodyParams p;
  p.J_B_kg_m2 = Eigen::Vector3d(2.0, 3.0, 4.0).asDiagonal();
  p.wheel_count = 1;
  p.wheel_axes_B.col(0) = axis;
  p.wheel_inertia_kg_m2(0) = inertia;
  p.wheel_max_torque_Nm(0) = 0.01;
  p.wheel_max_momentum_Nms(0) = 0.5;
  return p;
}

const auto kNoTorque = [](double, const RigidBodyState&) { return Eigen::Vector3d::Zero().eval(); };

}  // namespace

TEST_CASE("RigidBodyParams::validate", "[sim][body]") {
  CHECK(RigidBodyParams{}.validate().empty());
  CHECK(pyramidSpacecraft().validate().empty());

  RigidBodyParams p = pyramidSpacecraft();
  p.J_B_kg_m2(0, 1) = 0.2;
  CHECK(anyStartsWith(p.validate(), "J_B_kg_m2: must be symmetric"));

  p = pyramidSpacecraft();
  p.J_B_kg_m2 = Eigen::Vector3d(1.0, 2.0, -1.0).asDiagonal();
  CHECK(anyStartsWith(p.validate(), "J_B_kg_m2: must be positive definite"));

  p = pyramidSpacecraft();
  p.J_B_kg_m2 = Eigen::Vector3d(1.0, 1.0, 3.0).asDiagonal();
  CHECK(anyStartsWith(p.validate(), "J_B_kg_m2: principal moments"));

  p = pyramidSpacecraft();
  p.wheel_count = 5;
  CHECK(anyStartsWith(p.validate(), "wheel_count: 5 not in 0..4"));

  p = pyramidSpacecraft();
  p.wheel_axes_B.col(2) *= 1.1;
  p.wheel_inertia_kg_m2(1) = 0.0;
  p.wheel_max_torque_Nm(3) = -1.0;
  p.wheel_max_momentum_Nms(0) = std::numeric_limits<double>::quiet_NaN();
  const auto errors = p.validate();
  CHECK(errors.size() == 4);
  CHECK(anyStartsWith(errors, "wheel_axes_B[2]: must be a unit vector"));
  CHECK(anyStartsWith(errors, "wheel_inertia_kg_m2[1]: "));
  CHECK(anyStartsWith(errors, "wheel_max_torque_Nm[3]: "));
  CHECK(anyStartsWith(errors, "wheel_max_momentum_Nms[0]: "));

  GIVEN("absent wheels with unset fields") {
    p = pyramidSpacecraft();
    p.wheel_count = 2;
    p.wheel_axes_B.col(3).setZero();
    p.wheel_inertia_kg_m2(3) = 0.0;
    CHECK(p.validate().empty());
  }
  GIVEN("a rotor inertia as large as the body's about that axis") {
    p = withOneWheel(Eigen::Vector3d::UnitZ(), 4.0);
    CHECK(anyStartsWith(p.validate(), "wheel_inertia_kg_m2: J minus the rotors"));
  }
}

TEST_CASE("RigidBodyWheels momentum, speed and energy bookkeeping", "[sim][body]") {
  const RigidBodyParams p = pyramidSpacecraft();
  const RigidBodyWheels body(p);
  const Eigen::Quaterniond q = quatFromRotationVector(Eigen::Vector3d(0.4, -0.2, 1.0));
  const Eigen::Vector3d w(0.03, -0.02, 0.035);
  const Eigen::Vector4d speeds(100.0, -100.0, 80.0, -60.0);
  const RigidBodyState x = body.makeState(q, w, speeds);

  CHECK((body.wheelSpeeds_rad_s(x) - speeds).norm() < 1e-12);

  // Independent forms: rotor momentum relative to the body, locked-body energy
  // plus rotor spin energy ½ I_w (Ω² + 2 Ω aᵀω).
  Eigen::Vector3d h_rel = Eigen::Vector3d::Zero();
  double energy = 0.5 * w.dot(p.J_B_kg_m2 * w);
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d a = p.wheel_axes_B.col(i);
    const double Iw = p.wheel_inertia_kg_m2(i);
    h_rel += a * Iw * speeds(i);
    energy += 0.5 * Iw * (speeds(i) * speeds(i) + 2.0 * speeds(i) * a.dot(w));
  }
  CHECK((body.wheelMomentum_B_Nms(x) - h_rel).norm() < 1e-14);
  CHECK((body.totalMomentum_N_Nms(x) - q * (p.J_B_kg_m2 * w + h_rel)).norm() < 1e-14);
  CHECK(body.kineticEnergy_J(x) == Approx(energy).epsilon(1e-13));

  GIVEN("fewer fitted wheels than columns") {
    RigidBodyParams three = p;
    three.wheel_count = 3;
    const RigidBodyWheels body3(three);
    const RigidBodyState x3 = body3.makeState(q, w, speeds);
    CHECK(body3.wheelSpeeds_rad_s(x3)(3) == 0.0);
    CHECK(x3.h_wheels_Nms(3) == 0.0);
  }
}

TEST_CASE("Torque-free gyrostat conserves momentum and energy over an orbit", "[sim][body]") {
  const RigidBodyParams p = pyramidSpacecraft();
  const RigidBodyWheels body(p);
  const RigidBodyState x0 = body.makeState(quatFromRotationVector(Eigen::Vector3d(0.4, -0.2, 1.0)),
                                           Eigen::Vector3d(0.03, -0.02, 0.035), Eigen::Vector4d(100, -100, 80, -60));
  const Eigen::Vector3d H0 = body.totalMomentum_N_Nms(x0);
  const double T0 = body.kineticEnergy_J(x0);
  constexpr double kDt = 0.1;
  constexpr int kSteps = 57000;  // one 5700 s orbit
  constexpr int kSubsteps = 4;

  WHEN("the motors are idle") {
    RigidBodyState x = x0;
    double max_norm_error = 0.0;
    for (int k = 0; k < kSteps; ++k) {
      x = body.propagate(x, k * kDt, kDt, kSubsteps, Eigen::Vector4d::Zero(), kNoTorque);
      max_norm_error = std::max(max_norm_error, std::abs(x.q_NB.norm() - 1.0));
    }
    THEN("H_N and kinetic energy are constant to 1e-9, |q| = 1 to 1e-12") {
      CHECK((body.totalMomentum_N_Nms(x) - H0).norm() < 1e-9 * H0.norm());
      CHECK(std::abs(body.kineticEnergy_J(x) - T0) < 1e-9 * T0);
      // The spinning rotors hold most of T; with h constant the body's share
      // ½ωᵀJ'ω is conserved on its own, which is the sensitive check.
      Eigen::Matrix3d J_spinless = p.J_B_kg_m2;
      for (int i = 0; i < 4; ++i) {
        J_spinless -= p.wheel_inertia_kg_m2(i) * p.wheel_axes_B.col(i) * p.wheel_axes_B.col(i).transpose();
      }
      const double body_energy0 = 0.5 * x0.w_NB_B.dot(J_spinless * x0.w_NB_B);
      CHECK(std::abs(0.5 * x.w_NB_B.dot(J_spinless * x.w_NB_B) - body_energy0) < 1e-9 * body_energy0);
      CHECK(max_norm_error < 1e-12);
      CHECK((x.h_wheels_Nms - x0.h_wheels_Nms).norm() == 0.0);
    }
  }
  WHEN("the motors exchange a constant internal torque") {
    const Eigen::Vector4d tau_m(2e-5, -1e-5, 1e-5, -2e-5);
    RigidBodyState x = x0;
    for (int k = 0; k < kSteps; ++k) x = body.propagate(x, k * kDt, kDt, kSubsteps, tau_m, kNoTorque);
    THEN("H_N is still constant and the wheels absorbed τ_m t") {
      CHECK((body.totalMomentum_N_Nms(x) - H0).norm() < 1e-9 * H0.norm());
      CHECK((x.h_wheels_Nms - (x0.h_wheels_Nms + tau_m * kSteps * kDt)).norm() < 1e-11);
      CHECK(std::abs(x.q_NB.norm() - 1.0) < 1e-12);
    }
  }
}

TEST_CASE("Constant external torque about a principal axis", "[sim][body]") {
  GIVEN("a body at rest without wheels and τ = 0.01 N m about y (J_y = 3)") {
    RigidBodyParams p;
    p.J_B_kg_m2 = Eigen::Vector3d(2.0, 3.0, 4.0).asDiagonal();
    const RigidBodyWheels body(p);
    const Eigen::Vector3d tau(0.0, 0.01, 0.0);
    const double t = 20.0;
    const RigidBodyState x = body.propagate(RigidBodyState{}, 0.0, t, 200, Eigen::Vector4d::Zero(),
                                            [&](double, const RigidBodyState&) { return tau; });
    THEN("ω = τ t / J and the rotation angle is ½ τ t² / J") {
      CHECK((x.w_NB_B - Eigen::Vector3d(0.0, 0.01 * t / 3.0, 0.0)).norm() < 1e-13);
      const Eigen::Vector3d angle = rotationVectorFromQuat(x.q_NB);
      CHECK((angle - Eigen::Vector3d(0.0, 0.5 * 0.01 * t * t / 3.0, 0.0)).norm() < 1e-10);
    }
  }
}

TEST_CASE("Wheel torque spins the body the opposite way", "[sim][body]") {
  GIVEN("one wheel on the z principal axis, I_w = 0.01, body at rest") {
    const double Iw = 0.01;
    const RigidBodyWheels body(withOneWheel(Eigen::Vector3d::UnitZ(), Iw));
    const double Jz_spinless = 4.0 - Iw;
    const double tau_m = 1e-3;
    const double t = 50.0;
    const RigidBodyState x =
        body.propagate(RigidBodyState{}, 0.0, t, 500, Eigen::Vector4d(tau_m, 0.0, 0.0, 0.0), kNoTorque);
    THEN("h = τ t, J'_z ω_z = −τ t, Ω = τ t (1/I_w + 1/J'_z), H = 0") {
      CHECK(x.h_wheels_Nms(0) == Approx(tau_m * t).epsilon(1e-14));
      CHECK((x.w_NB_B - Eigen::Vector3d(0.0, 0.0, -tau_m * t / Jz_spinless)).norm() < 1e-14);
      CHECK(body.wheelSpeeds_rad_s(x)(0) == Approx(tau_m * t * (1.0 / Iw + 1.0 / Jz_spinless)).epsilon(1e-13));
      CHECK(body.totalMomentum_N_Nms(x).norm() < 1e-15);
      const Eigen::Vector3d angle = rotationVectorFromQuat(x.q_NB);
      CHECK((angle - Eigen::Vector3d(0.0, 0.0, -0.5 * tau_m * t * t / Jz_spinless)).norm() < 1e-10);
    }
  }
}

TEST_CASE("limitMotorTorque saturates torque and momentum", "[sim][body]") {
  const RigidBodyParams p = pyramidSpacecraft();  // 0.01 N m, 0.3 N m s, I_w = 2e-3
  const RigidBodyWheels body(p);
  const Eigen::Vector3d w(0.01, 0.02, -0.01);

  WHEN("the wheels are well inside their momentum range") {
    const RigidBodyState x = body.makeState(Eigen::Quaterniond::Identity(), w, Eigen::Vector4d(10, -10, 0, 50));
    const Eigen::Vector4d tau =
        body.limitMotorTorque(x, Eigen::Vector4d(0.05, -0.05, 0.004, std::numeric_limits<double>::quiet_NaN()));
    THEN("commands are clamped to ±max torque and non-finite ones dropped") {
      CHECK(tau == Eigen::Vector4d(0.01, -0.01, 0.004, 0.0));
    }
  }
  WHEN("wheels sit at +max and −max relative momentum (Ω = ±150 rad/s)") {
    const RigidBodyState x = body.makeState(Eigen::Quaterniond::Identity(), w, Eigen::Vector4d(150, -150, 150, -150));
    const Eigen::Vector4d tau = body.limitMotorTorque(x, Eigen::Vector4d(0.005, -0.005, -0.02, 0.02));
    THEN("torque that would push further is refused, torque back into range passes") {
      CHECK(tau == Eigen::Vector4d(0.0, 0.0, -0.01, 0.01));
    }
  }
  WHEN("a wheel is not fitted") {
    RigidBodyParams three = p;
    three.wheel_count = 3;
    const RigidBodyWheels body3(three);
    const Eigen::Vector4d tau = body3.limitMotorTorque(RigidBodyState{}, Eigen::Vector4d::Constant(0.001));
    CHECK(tau == Eigen::Vector4d(0.001, 0.001, 0.001, 0.0));
  }
}

TEST_CASE("Wheel friction parameters are validated", "[sim][actuators]") {
  RigidBodyParams p = pyramidSpacecraft();
  p.wheel_viscous_friction_Nms_rad(1) = -1e-6;
  p.wheel_coulomb_friction_Nm(2) = std::numeric_limits<double>::infinity();
  const auto errors = p.validate();
  CHECK(errors.size() == 2);
  CHECK(anyStartsWith(errors, "wheel_viscous_friction_Nms_rad[1]: "));
  CHECK(anyStartsWith(errors, "wheel_coulomb_friction_Nm[2]: "));
  p.wheel_count = 1;  // absent wheels are not checked
  CHECK(p.validate().empty());
}

TEST_CASE("A coasting wheel spins down as the friction law's closed form", "[sim][actuators]") {
  // One wheel on the z principal axis, body at rest: only z moves. The friction
  // τ_f on the rotor and −τ_f on the body give I_eff Ω̇ = τ_f for the relative
  // speed, 1/I_eff = 1/I_w + 1/J'_z. With τ_f = −c_v Ω − c_c sgn Ω and Ω0 > 0:
  //   viscous   Ω = Ω0 e^(−t/T),  T = I_eff / c_v
  //   Coulomb   Ω = Ω0 − c_c t / I_eff,  stops at t* = I_eff Ω0 / c_c
  //   both      Ω = (Ω0 + c_c/c_v) e^(−t/T) − c_c/c_v,  t* = T ln(1 + c_v Ω0 / c_c)
  const double Iw = 0.01;
  const double Jz_spinless = 4.0 - Iw;
  const double I_eff = 1.0 / (1.0 / Iw + 1.0 / Jz_spinless);
  constexpr double kDt = 0.1;
  constexpr int kSubsteps = 4;
  const auto coast = [&](double c_v, double c_c, double omega0, double t_end, auto&& expected, double t_stop) {
    RigidBodyParams p = withOneWheel(Eigen::Vector3d::UnitZ(), Iw);
    p.wheel_viscous_friction_Nms_rad(0) = c_v;
    p.wheel_coulomb_friction_Nm(0) = c_c;
    const RigidBodyWheels body(p);
    RigidBodyState x = body.makeState(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero(),
                                      Eigen::Vector4d(omega0, 0.0, 0.0, 0.0));
    const int steps = static_cast<int>(std::lround(t_end / kDt));
    const Eigen::Vector3d H0 = body.totalMomentum_N_Nms(x);
    double max_error = 0.0;
    double min_speed = omega0;
    double max_momentum = 0.0;  // relative to |H0|
    for (int k = 1; k <= steps; ++k) {
      x = body.propagate(x, (k - 1) * kDt, kDt, kSubsteps, Eigen::Vector4d::Zero(), kNoTorque);
      const double t = k * kDt;
      const double speed = body.wheelSpeeds_rad_s(x)(0);
      min_speed = std::min(min_speed, speed);
      max_momentum = std::max(max_momentum, (body.totalMomentum_N_Nms(x) - H0).norm() / H0.norm());
      if (t < t_stop - kDt) max_error = std::max(max_error, std::abs(speed - expected(t)));
    }
    struct Result {
      double max_error, min_speed, final_speed, max_momentum;
    };
    return Result{max_error, min_speed, body.wheelSpeeds_rad_s(x)(0), max_momentum};
  };
  const double kNever = std::numeric_limits<double>::infinity();

  WHEN("the bearing is viscous only (c_v = 1e-4 N m s/rad, Ω0 = 100 rad/s)") {
    const double c_v = 1e-4;
    const auto r = coast(c_v, 0.0, 100.0, 300.0, [&](double t) { return 100.0 * std::exp(-c_v * t / I_eff); }, kNever);
    THEN("Ω decays exponentially with T = I_eff / c_v ≈ 99.8 s") {
      CHECK(r.max_error < 1e-9);
      CHECK(r.max_momentum < 1e-12);  // friction is internal: H_N = I_w Ω0 ẑ throughout (relative)
    }
  }
  WHEN("the friction is dry only (c_c = 1e-3 N m, Ω0 = 10 rad/s, t* ≈ 99.8 s)") {
    const double c_c = 1e-3;
    const double t_stop = I_eff * 10.0 / c_c;
    const auto r = coast(0.0, c_c, 10.0, 150.0, [&](double t) { return 10.0 - c_c * t / I_eff; }, t_stop);
    THEN("Ω falls linearly, stops at t* and never reverses") {
      CHECK(r.max_error < 1e-11);
      CHECK(r.min_speed >= 0.0);
      CHECK(std::abs(r.final_speed) < 1e-12);
      CHECK(r.max_momentum < 1e-12);
    }
  }
  WHEN("both act (c_v = 1e-4, c_c = 1e-3, Ω0 = 100 rad/s)") {
    const double c_v = 1e-4;
    const double c_c = 1e-3;
    const double T = I_eff / c_v;
    const double t_stop = T * std::log(1.0 + c_v * 100.0 / c_c);  // ≈ 239 s
    const auto r = coast(c_v, c_c, 100.0, 300.0,
                         [&](double t) { return (100.0 + c_c / c_v) * std::exp(-t / T) - c_c / c_v; }, t_stop);
    THEN("Ω follows the combined closed form to the stop and rests there") {
      CHECK(t_stop == Approx(239.2).epsilon(1e-3));
      CHECK(r.max_error < 1e-9);
      CHECK(r.min_speed >= 0.0);
      CHECK(std::abs(r.final_speed) < 1e-12);
    }
  }
}

TEST_CASE("Motor torque against friction settles at the balance speed", "[sim][actuators]") {
  GIVEN("τ_m = 5e-3 N m, c_v = 1e-3 N m s/rad, c_c = 1e-3 N m, Ω0 = 1 rad/s") {
    const double Iw = 0.01;
    RigidBodyParams p = withOneWheel(Eigen::Vector3d::UnitZ(), Iw);
    p.wheel_viscous_friction_Nms_rad(0) = 1e-3;
    p.wheel_coulomb_friction_Nm(0) = 1e-3;
    const RigidBodyWheels body(p);
    const double I_eff = 1.0 / (1.0 / Iw + 1.0 / (4.0 - Iw));
    const double omega_ss = (5e-3 - 1e-3) / 1e-3;  // 4 rad/s
    RigidBodyState x = body.makeState(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero(),
                                      Eigen::Vector4d(1.0, 0.0, 0.0, 0.0));
    const Eigen::Vector4d tau_m(5e-3, 0.0, 0.0, 0.0);
    const Eigen::Vector3d H0 = body.totalMomentum_N_Nms(x);
    double max_error = 0.0;
    for (int k = 1; k <= 3000; ++k) {  // 300 s = 30 time constants
      x = body.propagate(x, (k - 1) * 0.1, 0.1, 4, tau_m, kNoTorque);
      const double expected = omega_ss + (1.0 - omega_ss) * std::exp(-1e-3 * k * 0.1 / I_eff);
      max_error = std::max(max_error, std::abs(body.wheelSpeeds_rad_s(x)(0) - expected));
    }
    THEN("Ω = Ω_ss + (Ω0 − Ω_ss) e^(−c_v t / I_eff), Ω_ss = (τ_m − c_c) / c_v; friction balances the motor") {
      CHECK(max_error < 1e-9);
      CHECK(body.wheelSpeeds_rad_s(x)(0) == Approx(omega_ss).epsilon(1e-12));
      CHECK(body.frictionTorque_Nm(x, 0.025)(0) == Approx(-5e-3).epsilon(1e-12));
      CHECK((body.totalMomentum_N_Nms(x) - H0).norm() < 1e-15);  // the motor torque is internal too
    }
  }
}

TEST_CASE("Friction torque: sign law outside the stiction band, ramp inside", "[sim][actuators]") {
  const double Iw = 0.01;
  RigidBodyParams p = withOneWheel(Eigen::Vector3d::UnitZ(), Iw);
  p.wheel_viscous_friction_Nms_rad(0) = 2e-4;
  p.wheel_coulomb_friction_Nm(0) = 1e-3;
  const RigidBodyWheels body(p);
  const double h = 0.025;
  const double band = 1e-3 * h * (1.0 / Iw + 1.0 / (4.0 - Iw));  // Ω_ε = c_c h / I_eff
  const auto friction = [&](double speed, double substep) {
    return body.frictionTorque_Nm(body.makeState(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero(),
                                                 Eigen::Vector4d(speed, 0.0, 0.0, 0.0)),
                                  substep)(0);
  };
  CHECK(friction(-50.0, h) == Approx(-2e-4 * -50.0 + 1e-3).epsilon(1e-14));
  CHECK(friction(2.0 * band, h) == Approx(-2e-4 * 2.0 * band - 1e-3).epsilon(1e-14));
  CHECK(friction(0.5 * band, h) == Approx(-2e-4 * 0.5 * band - 0.5e-3).epsilon(1e-12));
  CHECK(friction(0.0, h) == 0.0);
  CHECK(friction(0.0, 0.0) == 0.0);  // bare sign law: sgn 0 = 0
  CHECK(friction(1e-9, 0.0) == Approx(-1e-3).epsilon(1e-6));
}
