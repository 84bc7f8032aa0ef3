// SPDX-License-Identifier: Apache-2.0
// DynamicsModel with the attitude held on the east–north–zenith frame (ideal
// attitude control, seed S3's minute-long steps): the body follows the frame,
// the total angular momentum changes by the external angular impulse alone
// and the wheels hold what the body does not; the truth's thruster totals.
#include <cmath>
#include <numbers>

#include <catch2/catch.hpp>

#include "sim/Constants.hpp"
#include "sim/DynamicsModel.hpp"
#include "sim/Frames.hpp"
#include "tests/unit/sim/PyramidWheels.hpp"

using namespace flatsat::sim;

namespace {

constexpr SimTime kMinute = 60'000'000'000;

/// A geostationary spacecraft on a Kepler orbit with a pyramid of wheels, a
/// constant disturbance torque and one thruster off the centre of mass.
DynamicsParams heldGeo() {
  DynamicsParams p;
  p.orbit.semi_major_axis_m = 42164.0e3;
  p.body.J_B_kg_m2 = Eigen::Vector3d(3000.0, 1500.0, 3500.0).asDiagonal();
  test::fitPyramidWheels(p.body);
  p.body.wheel_max_momentum_Nms = Eigen::Vector4d::Constant(50.0);
  p.gravity_gradient = false;
  p.disturbance_torque_B_Nm = Eigen::Vector3d(2e-5, -1e-5, 3e-5);
  ThrusterParams thruster;
  thruster.r_B_m = {0.0, 1.2, 0.9};
  thruster.direction_B = Eigen::Vector3d(0.1, -0.8, -0.6).normalized();
  thruster.thrust_N = 0.165;
  p.thrusters = {thruster};
  p.attitude_held = true;
  p.substeps = 1;
  return p;
}

}  // namespace

TEST_CASE("Held attitude: the body rides the east-north-zenith frame, the wheels take the external torques",
          "[sim][held]") {
  DynamicsParams p = heldGeo();
  DynamicsModel model(p);
  const Eigen::Vector3d H0 = model.truth().H_total_N_Nms;
  Eigen::Vector3d angular_impulse = Eigen::Vector3d::Zero();
  ActuatorCommands cmd;
  for (int k = 0; k < 24 * 60; ++k) {
    const Truth before = model.truth();
    cmd.thruster_on_time_s(0) = (k / 60) % 3 == 0 ? 60.0 : 0.0;  // an hour on, two off
    model.step(cmd, (k + 1) * kMinute);
    const Truth& t = model.truth();
    // The frame of the state the step ended on, turning at the orbit's rate.
    const Eigen::Matrix3d R = R_N_EastNorthZenith(t.r_N_m, t.v_N_m_s);
    CHECK((t.q_NB.toRotationMatrix() - R).norm() < 1e-12);
    const Eigen::Vector3d w_N = t.r_N_m.cross(t.v_N_m_s) / t.r_N_m.squaredNorm();
    CHECK((t.q_NB * t.w_NB_B_rad_s - w_N).norm() < 1e-15);
    // The torque of the step's middle, in the body held over the step.
    const Eigen::Vector3d tau_B = p.disturbance_torque_B_Nm + t.tau_thruster_B_Nm;
    angular_impulse += 60.0 * (before.q_NB.slerp(0.5, t.q_NB) * tau_B);
  }
  const Eigen::Vector3d H = model.truth().H_total_N_Nms;
  // Over a day the thruster's torque (r × F = 0.2 N m while on, turning with the body) dominates.
  CHECK(angular_impulse.norm() > 100.0);
  CHECK((H - H0 - angular_impulse).norm() < 1e-3 * angular_impulse.norm());
  // The wheels hold all of it but the body's own J ω.
  const Truth& t = model.truth();
  const Eigen::Vector3d body_N = t.q_NB * (p.body.J_B_kg_m2 * t.w_NB_B_rad_s);
  CHECK((t.q_NB * t.h_wheels_B_Nms + body_N - H).norm() < 1e-6 * H.norm());
}

TEST_CASE("Truth totals count every burn and its impulse since the start", "[sim][held]") {
  DynamicsModel model(heldGeo());
  ActuatorCommands cmd;
  const double on_s[] = {60.0, 30.0, 0.0, 0.0, 12.0, 0.0, 60.0, 60.0, 60.0};  // three burns
  for (int k = 0; k < 9; ++k) {
    cmd.thruster_on_time_s(0) = on_s[k];
    model.step(cmd, (k + 1) * kMinute);
  }
  const Truth& t = model.truth();
  CHECK(t.thruster_burns[0] == 3);
  CHECK(t.thruster_burns[1] == 0);
  CHECK(t.thruster_impulse_total_Ns(0) == Approx(0.165 * 282.0).epsilon(1e-12));
  model.reset();
  CHECK(model.truth().thruster_burns[0] == 0);
  CHECK(model.truth().thruster_impulse_total_Ns(0) == 0.0);
}
