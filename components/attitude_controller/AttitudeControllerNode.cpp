// SPDX-License-Identifier: Apache-2.0
#include "components/attitude_controller/AttitudeControllerNode.hpp"

#include "bus/Convert.hpp"
#include "components/Processes.hpp"
#include "components/common/onboard/ReferenceParams.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::attitude_controller {

namespace {

SunPointingControllerInput toInput(const msg::AttitudeEstimate& estimate,
                                   const msg::WheelTachReading& tach) {
  SunPointingControllerInput in;
  in.sun_B_est_unit = bus::vec3(estimate.sun_body_unit());
  in.w_NB_B_rad_s = bus::vec3(estimate.w_body_rad_s());
  in.wheel_speed_rad_s = bus::vec4(tach.wheel_speed_rad_s());
  in.valid = estimate.valid();
  return in;
}

msg::WheelTorqueCmd toMessage(const SunPointingControllerOutput& out) {
  msg::WheelTorqueCmd m;
  bus::put(m.torque_Nm(), out.wheel_torque_Nm);
  bus::put(m.tau_body_cmd_Nm(), out.tau_cmd_B_Nm);
  m.pointing_error_rad(out.pointing_error_rad);
  m.saturated(out.saturated);
  return m;
}

}  // namespace

AttitudeControllerNode::AttitudeControllerNode(bus::Bus& bus, bus::NodeOptions options,
                                               const AttitudeControllerNodeParams& params)
    : Component(bus, std::move(options)),
      controller_(params.law),
      params_(bus, name(),
              {{"kp_Nm_per_rad", [](SunPointingControllerParams& p) -> double& { return p.kp_Nm_per_rad; }},
               {"kd_Nm_s_per_rad", [](SunPointingControllerParams& p) -> double& { return p.kd_Nm_s_per_rad; }},
               {"max_torque_Nm", [](SunPointingControllerParams& p) -> double& { return p.max_torque_Nm; }},
               {"max_rate_rad_s", [](SunPointingControllerParams& p) -> double& { return p.max_rate_rad_s; }}}) {
  if (params.s2_orbital) onboard_.emplace(*params.s2_orbital);
}

void AttitudeControllerNode::step(const bus::StepContext& ctx) {
  // The law's plain numbers are settable; the wheel geometry and the axis stay fixed.
  if (auto changed = params_.take(controller_.params(), [](const SunPointingControllerParams& p) { return p.validate(); },
                                  acks_, ctx)) {
    controller_ = SunPointingController(*changed);
  }
  acks_.publish(ctx, name());
  const auto tach = tach_.at(ctx.step);
  const auto used = last_tach_.update(tach);
  const auto estimate = estimate_.at(ctx.step);
  SunPointingControllerOutput out;
  if (onboard_) {
    const auto reference = onboard_->step(ctx.sim_time_ns);
    AttitudeTargetInput in = s2OrbitalTarget(reference.r_N_m, reference.v_N_m_s);
    in.q_NB_est = bus::quat(estimate.q_inertial_body());
    in.w_NB_B_rad_s = bus::vec3(estimate.w_body_rad_s());
    in.wheel_speed_rad_s = bus::vec4(used.wheel_speed_rad_s());
    in.valid = estimate.valid() && in.q_NB_est.coeffs().allFinite() && in.q_NB_est.norm() > 0.0;
    out = controller_.hold(in, ctx.sim_time_ns);
  } else {
    out = controller_.step(toInput(estimate, used), ctx.sim_time_ns);
  }
  auto message = toMessage(out);
  bus::stamp(message.header(), ctx, name());
  command_.write(message);
}

AttitudeControllerNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                        const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  const vehicle::VehicleDescription& known = vehicle.onboard;  // flight software sees only this
  AttitudeControllerNodeParams node;
  SunPointingControllerParams& p = node.law;
  p.wheels = wheelGeometryOf(known.body);
  auto r = scenario.componentParams(args.name, problems);
  vehicle::refuseMovedKeys(r, vehicle::kMovedReferenceKeys);
  r.read("kp_Nm_per_rad", p.kp_Nm_per_rad, "N m/rad");
  r.read("kd_Nm_s_per_rad", p.kd_Nm_s_per_rad, "N m s/rad");
  r.read("max_torque_Nm", p.max_torque_Nm, "N m");
  r.read("max_rate_rad_s", p.max_rate_rad_s, "rad/s");
  r.read("pointing_axis_body", p.pointing_axis_B, "-");
  std::string target = "sun";
  r.read("target", target);
  const double field_node_s = onboard::readFieldNodeSpacing(r);
  if (target == "s2_orbital") {
    node.s2_orbital = onboard::referenceModelOf(known, field_node_s);
  } else if (target != "sun") {
    r.problem("target", "must be sun or s2_orbital, not \"" + target + "\"");
  }
  r.problems(p.validate());
  r.finish();
  return node;
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<AttitudeControllerNode>(argc, argv, "attitude_controller", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::attitude_controller
