// SPDX-License-Identifier: Apache-2.0
#include "sim/DynamicsModel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/Constants.hpp"
#include "sim/Disturbances.hpp"
#include "sim/Frames.hpp"
#include "sim/Geodetic.hpp"
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

// The numerical orbit's drag takes the model's atmosphere.
OrbitTrackParams orbitTrackParams(const DynamicsParams& params) {
  OrbitTrackParams track = params.orbit_track;
  if (params.atmosphere) track.forces.atmosphere = *params.atmosphere;
  return track;
}

template <class T>
T lerp(const T& a, const T& b, double s) {
  return a + s * (b - a);
}

// Degree-truncated coefficients (the loaders give every degree of the model).
GaussCoefficients truncated(GaussCoefficients coefficients, int degree) {
  coefficients.degree = std::min(coefficients.degree, degree);
  return coefficients;
}

}  // namespace

DynamicsModel::DynamicsModel(const DynamicsParams& params)
    : params_(validated(params)),
      orbit_(orbitTrackParams(params), params.orbit, params.epoch),
      body_(params.body),
      dipole_(params.field),
      thrusters_(params.thrusters),
      jd_epoch_(julianDate(params.epoch)) {
  if (params.field_model == FieldModel::kSphericalHarmonics) {
    harmonics_.emplace(truncated(params.field_harmonics, params.field_degree));
  }
  if (params.atmosphere) atmosphere_.emplace(*params.atmosphere);
  if (params.flaps.fitted) flaps_.emplace(params.flaps);
  reset();
}

void DynamicsModel::reset() {
  t_ = 0;
  truth_ = Truth{};
  state_ = body_.makeState(params_.q0_NB, params_.w0_NB_B_rad_s, params_.wheel_speed0_rad_s);
  orbit_.reset();
  env_ = environmentAt(0.0);
  truth_torques_.reset();
  if (params_.attitude_held) {
    const RigidBodyState held = heldState(env_.orbit, Eigen::Vector3d::Zero());
    state_ = body_.makeState(held.q_NB, held.w_NB_B, params_.wheel_speed0_rad_s);
  }
  setFlaps(Eigen::Vector4d::Zero());
  updateTruth(Applied{}, 0.0);
}

void DynamicsModel::step(const ActuatorCommands& cmd, SimTime t_next) {
  if (t_next <= t_) return;
  const double t0_s = toSeconds(t_);
  const double t1_s = toSeconds(t_next);
  const double dt_s = t1_s - t0_s;
  Applied applied;
  commands_clamped_ = commandsBeyondLimits(cmd);
  applied.wheel_torque_Nm = body_.limitMotorTorque(state_, cmd.wheel_torque_Nm);
  applied.dipole_B_Am2 = clipDipole(cmd.dipole_B_Am2);
  const double quiet = cmd.dipole_quiet_fraction;
  applied.dipole_on_fraction = quiet > 0.0 && quiet < 1.0 ? 1.0 - quiet : 1.0;
  applied.thrusters = thrusters_.fire(cmd.thruster_on_time_s, cmd.thruster_gimbal_rad, dt_s);
  if (flaps_) applied.flap_angle_rad = flaps_->limitAngles(cmd.flap_angle_rad);
  setFlaps(applied.flap_angle_rad);
  const Environment next = environmentAt(t1_s);
  const auto torque_with = [&](const Eigen::Vector3d& dipole_B_Am2) {
    return [&, dipole_B_Am2](double t_s, const RigidBodyState& x) -> Eigen::Vector3d {
      // At the step's start the chord is env_ itself, the truth's environment.
      Environment between;
      const Environment& env = t_s == t0_s ? env_ : (between = interpolated(env_, next, (t_s - t0_s) / dt_s));
      return torquesAt(env, x.q_NB, dipole_B_Am2).total_B_Nm() + params_.disturbance_torque_B_Nm +
             applied.thrusters.torque_B_Nm;
    };
  };
  const Eigen::Quaterniond q_start = state_.q_NB;
  // Ideal attitude control: the external torques of the step's mid-point go
  // into the total momentum, which the wheels hold once the body is back on
  // its frame (the attitude a step of RK4 would take needs a controller's
  // bandwidth far above 1/step at S3's minute-long steps).
  Eigen::Vector3d H_held_N_Nms = Eigen::Vector3d::Zero();
  if (params_.attitude_held) {
    RigidBodyState mid = state_;  // the frame half a step on, at the orbit's rate (midpoint rule)
    const Eigen::Vector3d& w = state_.w_NB_B;
    if (w.norm() > 0.0) mid.q_NB = state_.q_NB * Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * dt_s * w.norm(), w.normalized()));
    const Eigen::Vector3d tau_B = torque_with(applied.dipole_B_Am2)(t0_s + 0.5 * dt_s, mid);
    H_held_N_Nms = body_.totalMomentum_N_Nms(state_) + dt_s * (mid.q_NB * tau_B);
  } else {
    // A quiet part switches the coils off: the step is integrated in two pieces so
    // that no integrator stage straddles the switch.
    const double on_s = applied.dipole_on_fraction * dt_s;
    state_ = body_.propagate(state_, t0_s, on_s, params_.substeps, applied.wheel_torque_Nm,
                             torque_with(applied.dipole_B_Am2));
    if (on_s < dt_s) {
      state_ = body_.propagate(state_, t0_s + on_s, dt_s - on_s, params_.substeps, applied.wheel_torque_Nm,
                               torque_with(Eigen::Vector3d::Zero()));
    }
  }
  t_ = t_next;
  env_ = next;
  truth_torques_.reset();
  const Eigen::Vector3d& f_B = applied.thrusters.force_B_N;
  if (params_.orbit_track.propagator == OrbitPropagation::kNumerical && !f_B.isZero(0.0)) {
    const Eigen::Quaterniond q_end = params_.attitude_held ? heldState(env_.orbit, H_held_N_Nms).q_NB : state_.q_NB;
    const Eigen::Vector3d a_N = (q_start * f_B + q_end * f_B) / (2.0 * params_.orbit_track.forces.mass_kg);
    orbit_.kick(t1_s, 0.5 * dt_s * dt_s * a_N, dt_s * a_N);
    env_ = environmentAt(t1_s);
  }
  if (params_.attitude_held) state_ = heldState(env_.orbit, H_held_N_Nms);
  updateTruth(applied, dt_s / params_.substeps);
}

RigidBodyState DynamicsModel::heldState(const KeplerOrbit::State& orbit, const Eigen::Vector3d& H_N_Nms) const {
  const Eigen::Matrix3d R_NB = R_N_EastNorthZenith(orbit.r_N_m, orbit.v_N_m_s);
  const Eigen::Vector3d w_N = orbit.r_N_m.cross(orbit.v_N_m_s) / orbit.r_N_m.squaredNorm();
  return body_.heldAt(Eigen::Quaterniond(R_NB), R_NB.transpose() * w_N, H_N_Nms);
}

void DynamicsModel::setFlaps(const Eigen::Vector4d& flap_angle_rad) {
  if (flaps_) flap_panels_ = flaps_->panels(flap_angle_rad);
}

DynamicsModel::Environment DynamicsModel::environmentAt(double t_s) {
  Environment env;
  env.orbit = orbit_.at(t_s);
  const Eigen::Vector3d& r_N = env.orbit.r_N_m;
  const Eigen::Matrix3d R_EN_now = R_EN(jd_epoch_ + t_s / kSecondsPerDay);
  env.r_E_m = R_EN_now * r_N;
  env.b_N_T = R_EN_now.transpose() * (harmonics_ ? harmonics_->b_E_T(env.r_E_m) : dipole_.b_E_T(env.r_E_m));
  env.wind_N_m_s = -velocityThroughAir_N_m_s(r_N, env.orbit.v_N_m_s);
  env.r_sun_N_m = sunPosition_N_m(jd_epoch_ + (t_s + kTtMinusUtc_s) / kSecondsPerDay);
  env.illumination = illumination(r_N, env.r_sun_N_m);
  env.solar_flux_W_m2 = solarFlux_W_m2((env.r_sun_N_m - r_N).norm(), env.illumination);
  env.density_kg_m3 =
      atmosphere_ ? atmosphere_->density_kg_m3(r_N, env.r_sun_N_m.normalized()) : params_.density_kg_m3;
  return env;
}

DynamicsModel::Environment DynamicsModel::interpolated(const Environment& a, const Environment& b, double s) {
  Environment env;
  env.orbit.r_N_m = lerp(a.orbit.r_N_m, b.orbit.r_N_m, s);
  env.orbit.v_N_m_s = lerp(a.orbit.v_N_m_s, b.orbit.v_N_m_s, s);
  env.r_E_m = lerp(a.r_E_m, b.r_E_m, s);
  env.b_N_T = lerp(a.b_N_T, b.b_N_T, s);
  env.wind_N_m_s = lerp(a.wind_N_m_s, b.wind_N_m_s, s);
  env.r_sun_N_m = lerp(a.r_sun_N_m, b.r_sun_N_m, s);
  env.illumination = lerp(a.illumination, b.illumination, s);
  env.solar_flux_W_m2 = lerp(a.solar_flux_W_m2, b.solar_flux_W_m2, s);
  env.density_kg_m3 = lerp(a.density_kg_m3, b.density_kg_m3, s);
  return env;
}

Eigen::Vector3d DynamicsModel::Torques::total_B_Nm() const {
  return gravity_gradient_B_Nm + magnetic_B_Nm + residual_magnetic_B_Nm + aerodynamic.torque_B_Nm +
         solar_pressure.torque_B_Nm;
}

DynamicsModel::Torques DynamicsModel::attitudeTorquesAt(const Environment& env, const Eigen::Quaterniond& q_NB) const {
  // Four vectors turned by one attitude: as a matrix once, not a quaternion
  // product each (callgrind: a fifth of the cost of a call).
  const Eigen::Matrix3d R_BN = q_NB.toRotationMatrix().transpose();
  Torques torques;
  torques.b_B_T = R_BN * env.b_N_T;
  torques.wind_B_m_s = R_BN * env.wind_N_m_s;
  torques.sun_B_unit = R_BN * (env.r_sun_N_m - env.orbit.r_N_m).normalized();
  torques.gravity_gradient_B_Nm =
      params_.gravity_gradient ? gravityGradientTorque_B_Nm(R_BN * env.orbit.r_N_m, params_.body.J_B_kg_m2)
                               : Eigen::Vector3d::Zero();
  torques.residual_magnetic_B_Nm = params_.residual_dipole_B_Am2.cross(torques.b_B_T);
  torques.aerodynamic =
      aerodynamicForceTorque(params_.panels, env.density_kg_m3, torques.wind_B_m_s, torques.sun_B_unit);
  torques.solar_pressure = solarPressureForceTorque(params_.panels, torques.sun_B_unit, env.solar_flux_W_m2);
  return torques;
}

DynamicsModel::Torques DynamicsModel::torquesAt(const Environment& env, const Eigen::Quaterniond& q_NB,
                                                const Eigen::Vector3d& dipole_B_Am2) const {
  // The same inputs, bit for bit, as the truth's: the same sums.
  const bool at_truth = &env == &env_ && truth_torques_ && truth_torques_->q_NB.coeffs() == q_NB.coeffs();
  Torques torques = at_truth ? truth_torques_->torques : attitudeTorquesAt(env, q_NB);
  torques.magnetic_B_Nm = dipole_B_Am2.cross(torques.b_B_T);
  if (flaps_) {
    torques.flaps_aerodynamic = aerodynamicForceTorque(flap_panels_, env.density_kg_m3, torques.wind_B_m_s);
    torques.aerodynamic += torques.flaps_aerodynamic;
    torques.solar_pressure += solarPressureForceTorque(flap_panels_, torques.sun_B_unit, env.solar_flux_W_m2);
  }
  return torques;
}

std::uint32_t DynamicsModel::commandsBeyondLimits(const ActuatorCommands& cmd) const {
  std::uint32_t beyond = 0;
  for (int i = 0; i < 3; ++i) beyond += !(std::abs(cmd.dipole_B_Am2(i)) <= params_.torquer_max_dipole_Am2(i));
  const RigidBodyParams& body = params_.body;
  for (int i = 0; i < body.wheel_count; ++i) beyond += !(std::abs(cmd.wheel_torque_Nm(i)) <= body.wheel_max_torque_Nm(i));
  return beyond;
}

Eigen::Vector3d DynamicsModel::clipDipole(const Eigen::Vector3d& dipole_B_Am2) const {
  Eigen::Vector3d clipped = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const double limit = params_.torquer_max_dipole_Am2(i);
    if (std::isfinite(dipole_B_Am2(i))) clipped(i) = std::clamp(dipole_B_Am2(i), -limit, limit);
  }
  return clipped;
}

void DynamicsModel::updateTruth(const Applied& applied, double substep_s) {
  const Environment& env = env_;
  truth_torques_ = AttitudeTorques{state_.q_NB, attitudeTorquesAt(env, state_.q_NB)};
  const Torques torques = torquesAt(env, state_.q_NB, applied.dipole_B_Am2);

  Truth& truth = truth_;
  truth.t = t_;
  truth.q_NB = state_.q_NB;
  truth.w_NB_B_rad_s = state_.w_NB_B;
  truth.wheel_speed_rad_s = body_.wheelSpeeds_rad_s(state_);
  truth.wheel_torque_applied_Nm = applied.wheel_torque_Nm;
  truth.h_wheels_B_Nms = body_.wheelMomentum_B_Nms(state_);
  truth.H_total_N_Nms = body_.totalMomentum_N_Nms(state_);
  truth.r_N_m = env.orbit.r_N_m;
  truth.v_N_m_s = env.orbit.v_N_m_s;
  truth.geodetic = geodeticFromEarthFixed(env.r_E_m);
  truth.b_N_T = env.b_N_T;
  truth.b_B_T = torques.b_B_T;
  truth.sun_N_unit = (env.r_sun_N_m - env.orbit.r_N_m).normalized();
  truth.sun_B_unit = torques.sun_B_unit;
  truth.illumination = env.illumination;
  truth.density_kg_m3 = env.density_kg_m3;
  truth.dipole_applied_B_Am2 = applied.dipole_B_Am2;
  truth.dipole_at_t_B_Am2 = applied.dipole_on_fraction < 1.0 ? Eigen::Vector3d::Zero() : applied.dipole_B_Am2;
  truth.tau_gravity_gradient_B_Nm = torques.gravity_gradient_B_Nm;
  truth.tau_magnetic_B_Nm = torques.magnetic_B_Nm;
  truth.tau_disturbance_B_Nm = params_.disturbance_torque_B_Nm;
  truth.tau_residual_magnetic_B_Nm = torques.residual_magnetic_B_Nm;
  truth.wheel_friction_torque_Nm = body_.frictionTorque_Nm(state_, substep_s);
  truth.wind_B_m_s = torques.wind_B_m_s;
  truth.solar_flux_W_m2 = env.solar_flux_W_m2;
  truth.f_aerodynamic_B_N = torques.aerodynamic.force_B_N;
  truth.tau_aerodynamic_B_Nm = torques.aerodynamic.torque_B_Nm;
  truth.tau_flaps_B_Nm = torques.flaps_aerodynamic.torque_B_Nm;
  truth.f_flaps_B_N = torques.flaps_aerodynamic.force_B_N;
  truth.f_solar_pressure_B_N = torques.solar_pressure.force_B_N;
  truth.tau_solar_pressure_B_Nm = torques.solar_pressure.torque_B_Nm;
  truth.flap_angle_applied_rad = applied.flap_angle_rad;
  truth.f_thruster_B_N = applied.thrusters.force_B_N;
  truth.tau_thruster_B_Nm = applied.thrusters.torque_B_Nm;
  // Totals since t = 0, so that a recording decimated in time still accounts
  // for every burn (seed S3's ΔV per year and firings per thruster).
  for (int i = 0; i < kMaxThrusters; ++i) {
    if (applied.thrusters.impulse_Ns(i) > 0.0 && truth.thruster_impulse_Ns(i) == 0.0) ++truth.thruster_burns[i];
  }
  truth.thruster_impulse_total_Ns += applied.thrusters.impulse_Ns;
  truth.thruster_impulse_Ns = applied.thrusters.impulse_Ns;
  truth.thruster_gimbal_applied_rad = applied.thrusters.gimbal_rad;
}

}  // namespace flatsat::sim
