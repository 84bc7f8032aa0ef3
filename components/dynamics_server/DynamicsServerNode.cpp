// SPDX-License-Identifier: Apache-2.0
#include "components/dynamics_server/DynamicsServerNode.hpp"

#include <algorithm>

#include <spdlog/spdlog.h>

#include "bus/Convert.hpp"
#include "components/Processes.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::dynamics_server {

using sim::ActuatorCommands;
using sim::ActuatorFault;
using sim::Truth;

namespace {

using bus::put;

msg::TruthState toMessage(const Truth& truth, int wheel_count, const bus::StepContext& ctx,
                          const std::string& source) {
  msg::TruthState m;
  bus::stamp(m.header(), ctx, source);
  put(m.q_inertial_body(), truth.q_NB);
  put(m.w_body_rad_s(), truth.w_NB_B_rad_s);
  m.wheel_count(static_cast<std::uint32_t>(wheel_count));
  put(m.wheel_speed_rad_s(), truth.wheel_speed_rad_s);
  put(m.wheel_torque_Nm(), truth.wheel_torque_applied_Nm);
  put(m.h_wheels_body_Nms(), truth.h_wheels_B_Nms);
  put(m.h_total_inertial_Nms(), truth.H_total_N_Nms);
  put(m.r_inertial_m(), truth.r_N_m);
  put(m.v_inertial_m_s(), truth.v_N_m_s);
  put(m.b_inertial_T(), truth.b_N_T);
  put(m.b_body_T(), truth.b_B_T);
  put(m.sun_inertial_unit(), truth.sun_N_unit);
  put(m.sun_body_unit(), truth.sun_B_unit);
  m.illumination(truth.illumination);
  put(m.dipole_body_Am2(), truth.dipole_applied_B_Am2);
  put(m.tau_gravity_gradient_body_Nm(), truth.tau_gravity_gradient_B_Nm);
  put(m.tau_magnetic_body_Nm(), truth.tau_magnetic_B_Nm);
  put(m.tau_disturbance_body_Nm(), truth.tau_disturbance_B_Nm);
  m.latitude_rad(truth.geodetic.latitude_rad);
  m.longitude_rad(truth.geodetic.longitude_rad);
  m.altitude_m(truth.geodetic.height_m);
  m.density_kg_m3(truth.density_kg_m3);
  m.solar_flux_W_m2(truth.solar_flux_W_m2);
  put(m.tau_residual_magnetic_body_Nm(), truth.tau_residual_magnetic_B_Nm);
  put(m.wheel_friction_torque_Nm(), truth.wheel_friction_torque_Nm);
  put(m.f_aerodynamic_body_N(), truth.f_aerodynamic_B_N);
  put(m.tau_aerodynamic_body_Nm(), truth.tau_aerodynamic_B_Nm);
  put(m.tau_flaps_body_Nm(), truth.tau_flaps_B_Nm);
  put(m.f_flaps_body_N(), truth.f_flaps_B_N);
  put(m.f_solar_pressure_body_N(), truth.f_solar_pressure_B_N);
  put(m.tau_solar_pressure_body_Nm(), truth.tau_solar_pressure_B_Nm);
  put(m.flap_angle_rad(), truth.flap_angle_applied_rad);
  put(m.f_thruster_body_N(), truth.f_thruster_B_N);
  put(m.tau_thruster_body_Nm(), truth.tau_thruster_B_Nm);
  put(m.dipole_at_sample_body_Am2(), truth.dipole_at_t_B_Am2);
  put(m.thruster_impulse_total_Ns(), truth.thruster_impulse_total_Ns);
  m.thruster_burns(truth.thruster_burns);
  return m;
}

}  // namespace

DynamicsServerNode::DynamicsServerNode(bus::Bus& bus, bus::NodeOptions options,
                                       const DynamicsServerParams& params)
    : TimeMaster(bus, std::move(options), {params.step_period_ns, params.final_step}),
      wheel_count_(params.dynamics.body.wheel_count),
      model_(params.dynamics),
      fault_port_(bus, name(),
                  [wheels = params.dynamics.body.wheel_count,
                   thrusters = static_cast<int>(params.dynamics.thrusters.size())](
                      const msg::FaultCmd& command, ActuatorFault& fault) {
                    return vehicle::toActuatorFault(command, wheels, thrusters, fault);
                  },
                  fault_events_) {
  for (const auto& fault : params.faults) faults_.add(fault);
  if (options_.schedule.count(std::string(bus::topics::kWheelTorqueCmd.producer))) {
    wheel_cmd_ = &addInput(bus::topics::kWheelTorqueCmd);
  }
  if (options_.schedule.count(std::string(bus::topics::kDipoleCmd.producer))) {
    dipole_cmd_ = &addInput(bus::topics::kDipoleCmd);
  }
  // The coils' owner drives the flaps too, and publishes their angles only when fitted.
  if (params.dynamics.flaps.fitted && options_.schedule.count(std::string(bus::topics::kFlapCmd.producer))) {
    flap_cmd_ = &addInput(bus::topics::kFlapCmd);
  }
  if (options_.schedule.count(std::string(bus::topics::kThrusterCmd.producer))) {
    thruster_cmd_ = &addInput(bus::topics::kThrusterCmd);
  }
  if (!params.wheels_follow.empty()) {
    wheel_unit_ = &addInput(bus::topics::kWheelTach);
    wheel_unit_name_ = params.wheels_follow;
    body_ = params.dynamics.body;
  }
}

std::optional<Eigen::Vector4d> DynamicsServerNode::followUnit(const bus::StepContext& ctx) {
  // A unit answers within a step or two on a paced rig; older, it has fallen silent and
  // its bridge will lose its lease: meanwhile the commands drive the rotors, as they do
  // once the emulator's samples are back.
  constexpr std::uint64_t kFreshSteps = 3;
  // A unit answering each command stamps its answer to the commands of step k with k + 1
  // (the plant's own convention): here, as step k ends, that answer has come.
  const auto tach = wheel_unit_->atIfAny(ctx.step + 1);
  const bool fresh = tach && bus::text(tach->header().source()) == wheel_unit_name_ && tach->valid() &&
                     tach->header().step() + kFreshSteps >= ctx.step + 1;
  if (fresh != following_unit_) {
    if (fresh) {
      spdlog::info("{}: step {}: the wheels follow the unit behind {}", name(), ctx.step, wheel_unit_name_);
    } else {
      spdlog::warn("{}: step {}: no fresh speeds from {}: the commanded torques drive the wheels", name(), ctx.step,
                   wheel_unit_name_);
    }
    following_unit_ = fresh;
  }
  if (!fresh) return std::nullopt;
  // The unit is the rotors: the plant's catch up with its speeds over this step, the body
  // taking the opposite momentum (a momentum exchange, so the drift of one step is
  // corrected in the next, not accumulated).
  const auto& body = body_;
  const double dt_s = static_cast<double>(ctx.period_ns) * 1e-9;
  Eigen::Vector4d torque = Eigen::Vector4d::Zero();
  const Eigen::Vector4d unit = bus::vec4(tach->wheel_speed_rad_s());
  for (int i = 0; i < wheel_count_; ++i) {
    const double needed = body.wheel_inertia_kg_m2(i) * (unit(i) - model_.truth().wheel_speed_rad_s(i)) / dt_s;
    torque(i) = std::clamp(needed, -body.wheel_max_torque_Nm(i), body.wheel_max_torque_Nm(i));
  }
  wheel_cmd_age_steps_ = static_cast<std::int64_t>(ctx.step + 1) - static_cast<std::int64_t>(tach->header().step());
  return torque;
}

void DynamicsServerNode::publishStep(const bus::StepContext& ctx) {
  auto truth = toMessage(model_.truth(), wheel_count_, ctx, name());
  truth.wheel_cmd_age_steps(wheel_cmd_age_steps_);
  truth.dipole_cmd_age_steps(dipole_cmd_age_steps_);
  truth_.write(truth);
}

void DynamicsServerNode::advance(const bus::StepContext& ctx) {
  ActuatorCommands cmd;
  wheel_cmd_age_steps_ = dipole_cmd_age_steps_ = kNoCommand;
  if (wheel_cmd_ != nullptr && wheel_cmd_->hasAny(ctx.step)) {
    const auto wheels = wheel_cmd_->at(ctx.step);
    cmd.wheel_torque_Nm = bus::vec4(wheels.torque_Nm());
    wheel_cmd_age_steps_ = static_cast<std::int64_t>(ctx.step - wheels.header().step());
  }
  if (wheel_unit_ != nullptr) {
    if (const auto torque = followUnit(ctx)) cmd.wheel_torque_Nm = *torque;
  }
  if (dipole_cmd_ != nullptr && dipole_cmd_->hasAny(ctx.step)) {
    const auto dipole = dipole_cmd_->at(ctx.step);
    cmd.dipole_B_Am2 = bus::vec3(dipole.m_body_Am2());
    cmd.dipole_quiet_fraction = dipole.quiet_fraction();
    dipole_cmd_age_steps_ = static_cast<std::int64_t>(ctx.step - dipole.header().step());
  }
  if (flap_cmd_ != nullptr && flap_cmd_->hasAny(ctx.step)) {
    cmd.flap_angle_rad = bus::vec4(flap_cmd_->at(ctx.step).theta_rad());
  }
  if (thruster_cmd_ != nullptr && thruster_cmd_->hasAny(ctx.step)) {
    // On-times are pulses of their step: one held (paced, a late or dead
    // sequencer) is not fired again; one late fires once, when it comes.
    const auto thrusters = thruster_cmd_->at(ctx.step);
    if (!thruster_cmd_fired_ || thrusters.header().step() > *thruster_cmd_fired_) {
      thruster_cmd_fired_ = thrusters.header().step();
      cmd.thruster_on_time_s = Eigen::Map<const sim::ThrusterVector>(thrusters.on_time_s().data());
      cmd.thruster_gimbal_rad = Eigen::Map<const sim::ThrusterGimbals>(thrusters.gimbal_rad().data());
    }
  }
  fault_port_.take(ctx, [this](const ActuatorFault& fault) { return faults_.add(fault); });
  const std::uint32_t active = faults_.apply(cmd, ctx.sim_time_ns);
  fault_port_.publishEvents(active, faults_.count(),
                            [this](int i) -> const ActuatorFault& { return faults_.fault(i); }, ctx);
  model_.step(cmd, ctx.sim_time_ns + ctx.period_ns);
  if (const std::uint32_t clamped = model_.commandsClamped(); clamped > 0) {
    const std::uint64_t n = commands_clamped_ += clamped;
    if (n == clamped) spdlog::warn("{}: step {}: an actuator command beyond its limit was held to it", name(), ctx.step);
  }
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<DynamicsServerNode>(argc, argv, "dynamics_server", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::dynamics_server
