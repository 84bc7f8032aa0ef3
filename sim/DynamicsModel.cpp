// SPDX-License-Identifier: Apache-2.0
#include "sim/DynamicsModel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/Disturbances.hpp"
#include "sim/SunEphemeris.hpp"

namespace flatsat::sim {
namespace {

// Constructing the members needs valid params, so validation runs first.
const DynamicsParams& validated(const DynamicsParams& params) {
  const std::vector<std::string> errors = params.validate();
  if (!errors.empty()) {
    std::string message = "invalid dynamics parameters:";
    for (const std::string& error : errors) message += "\n  " + error;
    throw std::invalid_argument(message);
  }
  return params;
}

}  // namespace

DynamicsModel::DynamicsModel(const DynamicsParams& params)
    : params_(validated(params)),
      orbit_(params.orbit),
      body_(params.body),
      field_(params.field),
      jd_epoch_(julianDate(params.epoch)) {
  reset();
}

void DynamicsModel::reset() {
  t_ = 0;
  state_ = body_.makeState(params_.q0_NB, params_.w0_NB_B_rad_s, params_.wheel_speed0_rad_s);
  updateTruth(Eigen::Vector4d::Zero(), Eigen::Vector3d::Zero());
}

void DynamicsModel::step(const ActuatorCommands& cmd, SimTime t_next) {
  if (t_next <= t_) return;
  const Eigen::Vector4d wheel_torque = body_.limitMotorTorque(state_, cmd.wheel_torque_Nm);
  const Eigen::Vector3d dipole = clipDipole(cmd.dipole_B_Am2);
  const double t0_s = toSeconds(t_);
  const auto external_torque = [&](double t_s, const RigidBodyState& x) -> Eigen::Vector3d {
    const Torques torques = torquesAt(environmentAt(t_s), x.q_NB, dipole);
    return torques.gravity_gradient_B_Nm + torques.magnetic_B_Nm + params_.disturbance_torque_B_Nm;
  };
  state_ = body_.propagate(state_, t0_s, toSeconds(t_next) - t0_s, params_.substeps, wheel_torque, external_torque);
  t_ = t_next;
  updateTruth(wheel_torque, dipole);
}

DynamicsModel::Environment DynamicsModel::environmentAt(double t_s) const {
  const KeplerOrbit::State orbit = orbit_.at(t_s);
  const Eigen::Matrix3d R_EN_now = R_EN(jd_epoch_ + t_s / kSecondsPerDay);
  return Environment{orbit, R_EN_now.transpose() * field_.b_E_T(R_EN_now * orbit.r_N_m)};
}

DynamicsModel::Torques DynamicsModel::torquesAt(const Environment& env, const Eigen::Quaterniond& q_NB,
                                                const Eigen::Vector3d& dipole_B_Am2) const {
  const Eigen::Quaterniond q_BN = q_NB.conjugate();
  const Eigen::Vector3d b_B_T = q_BN * env.b_N_T;
  const Eigen::Vector3d tau_gg = params_.gravity_gradient
                                     ? gravityGradientTorque_B_Nm(q_BN * env.orbit.r_N_m, params_.body.J_B_kg_m2)
                                     : Eigen::Vector3d::Zero();
  return Torques{tau_gg, dipole_B_Am2.cross(b_B_T), b_B_T};
}

Eigen::Vector3d DynamicsModel::clipDipole(const Eigen::Vector3d& dipole_B_Am2) const {
  Eigen::Vector3d clipped = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const double limit = params_.torquer_max_dipole_Am2(i);
    if (std::isfinite(dipole_B_Am2(i))) clipped(i) = std::clamp(dipole_B_Am2(i), -limit, limit);
  }
  return clipped;
}

void DynamicsModel::updateTruth(const Eigen::Vector4d& wheel_torque_Nm, const Eigen::Vector3d& dipole_B_Am2) {
  const double t_s = toSeconds(t_);
  const Environment env = environmentAt(t_s);
  const Torques torques = torquesAt(env, state_.q_NB, dipole_B_Am2);
  const Eigen::Vector3d r_sun_N_m = sunPosition_N_m(jd_epoch_ + (t_s + kTtMinusUtc_s) / kSecondsPerDay);
  const Eigen::Quaterniond q_BN = state_.q_NB.conjugate();

  Truth& truth = truth_;
  truth.t = t_;
  truth.q_NB = state_.q_NB;
  truth.w_NB_B_rad_s = state_.w_NB_B;
  truth.wheel_speed_rad_s = body_.wheelSpeeds_rad_s(state_);
  truth.wheel_torque_applied_Nm = wheel_torque_Nm;
  truth.h_wheels_B_Nms = body_.wheelMomentum_B_Nms(state_);
  truth.H_total_N_Nms = body_.totalMomentum_N_Nms(state_);
  truth.r_N_m = env.orbit.r_N_m;
  truth.v_N_m_s = env.orbit.v_N_m_s;
  truth.b_N_T = env.b_N_T;
  truth.b_B_T = torques.b_B_T;
  truth.sun_N_unit = (r_sun_N_m - env.orbit.r_N_m).normalized();
  truth.sun_B_unit = q_BN * truth.sun_N_unit;
  truth.illumination = illumination(env.orbit.r_N_m, r_sun_N_m);
  truth.dipole_applied_B_Am2 = dipole_B_Am2;
  truth.tau_gravity_gradient_B_Nm = torques.gravity_gradient_B_Nm;
  truth.tau_magnetic_B_Nm = torques.magnetic_B_Nm;
  truth.tau_disturbance_B_Nm = params_.disturbance_torque_B_Nm;
}

}  // namespace flatsat::sim
