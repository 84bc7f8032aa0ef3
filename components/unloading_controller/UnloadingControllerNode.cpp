// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/UnloadingControllerNode.hpp"

#include "bus/Convert.hpp"
#include "sim/DynamicsServerParams.hpp"

namespace flatsat::unloading_controller {

namespace {

CrossProductUnloadingInput toInput(const msg::WheelTachReading& tach,
                                   const msg::MagnetometerReading& field) {
  return {bus::vec4(tach.wheel_speed_rad_s()), bus::vec3(field.b_body_T()),
          field.valid() && !field.saturated()};
}

msg::DipoleCmd toMessage(const CrossProductUnloadingOutput& out) {
  msg::DipoleCmd m;
  bus::put(m.m_body_Am2(), out.m_B_Am2);
  bus::put(m.h_wheels_body_Nms(), out.h_B_Nms);
  m.active(out.active);
  m.saturated(out.saturated);
  return m;
}

}  // namespace

UnloadingControllerNode::UnloadingControllerNode(bus::Bus& bus, bus::NodeOptions options,
                                                 const CrossProductUnloadingParams& params)
    : Component(bus, std::move(options)), law_(params) {}

void UnloadingControllerNode::step(const bus::StepContext& ctx) {
  const auto tach = tach_.at(ctx.step);
  const auto& used = last_tach_.update(tach);
  auto message = toMessage(
      law_.step(toInput(used, field_.at(ctx.step)), ctx.sim_time_ns));
  message.header(bus::makeHeader(ctx, name()));
  command_.write(message);
}

CrossProductUnloadingParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                                       bus::ConfigProblems& problems) {
  bus::ConfigProblems reported_by_dynamics_server;
  const auto plant = sim::readPlant(scenario, reported_by_dynamics_server);
  CrossProductUnloadingParams p;
  p.wheels = {plant.body.wheel_count, plant.body.wheel_axes_B, plant.body.wheel_inertia_kg_m2};
  p.max_dipole_Am2 = plant.torquer_max_dipole_Am2;
  auto r = scenario.componentParams(args.name, problems);
  r.read("enabled", p.enabled);
  r.read("gain_per_s", p.gain_per_s, "1/s");
  r.read("h_target_body_Nms", p.h_target_B_Nms, "N m s");
  r.read("h_start_Nms", p.h_start_Nms, "N m s");
  r.read("h_stop_Nms", p.h_stop_Nms, "N m s");
  r.read("min_field_T", p.min_field_T, "T");
  r.problems(p.validate());
  r.finish();
  return p;
}

}  // namespace flatsat::unloading_controller
