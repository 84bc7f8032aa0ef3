// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/UnloadingControllerNode.hpp"

#include <optional>
#include <string>

#include "bus/Convert.hpp"
#include "sim/DynamicsServerParams.hpp"

namespace flatsat::unloading_controller {

namespace {

std::optional<CoilRequest> toRequest(const msg::CoilRequest& m) {
  if (m.request_id() == 0) return std::nullopt;
  return CoilRequest{m.request_id(), bus::vec3(m.m_body_Am2()), m.quiet_s(), m.pulse_s(),
                     m.quiet_after_s()};
}

msg::CoilWindow toMessage(const CoilWindowReport& r) {
  msg::CoilWindow m;
  m.request_id(r.request_id);
  static constexpr msg::CoilWindowPhase kPhases[] = {
      msg::CoilWindowPhase::COIL_IDLE,  msg::CoilWindowPhase::COIL_QUIET,
      msg::CoilWindowPhase::COIL_PULSE, msg::CoilWindowPhase::COIL_QUIET_AFTER,
      msg::CoilWindowPhase::COIL_DONE,  msg::CoilWindowPhase::COIL_REFUSED};
  m.phase(kPhases[static_cast<int>(r.phase)]);
  m.t0_ns(r.t0_ns);
  m.t1_ns(r.t1_ns);
  m.pulse_end_ns(r.pulse_end_ns);
  m.t2_ns(r.t2_ns);
  bus::put(m.m_body_Am2(), r.m_B_Am2);
  return m;
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
                                                 const UnloadingControllerNodeParams& params)
    : Component(bus, std::move(options)),
      law_(params.law),
      arbiter_(params.law.max_dipole_Am2) {
  if (params.field_source == FieldSource::kMagnetometer) {
    magnetometer_ = &addInput(bus::topics::kMagnetometer);
  } else {
    field_estimate_ = &addInput(bus::topics::kFieldEstimate);
    coil_request_ = &addInput(bus::topics::kCoilRequest);
  }
}

void UnloadingControllerNode::step(const bus::StepContext& ctx) {
  const auto reading = tach_.at(ctx.step);
  const auto& tach = last_tach_.update(reading);
  CrossProductUnloadingInput in{bus::vec4(tach.wheel_speed_rad_s()), {}, false};
  if (magnetometer_ != nullptr) {
    const auto field = magnetometer_->at(ctx.step);
    in.b_B_T = bus::vec3(field.b_body_T());
    in.b_valid = field.valid() && !field.saturated();
  } else {
    const auto field = field_estimate_->at(ctx.step);
    in.b_B_T = bus::vec3(field.b_body_T());
    in.b_valid = field.valid();
  }
  const auto law = law_.step(in, ctx.sim_time_ns);
  std::optional<CoilRequest> request;
  if (coil_request_ != nullptr) request = toRequest(coil_request_->at(ctx.step));
  const auto coils = arbiter_.step(request, law.m_B_Am2, ctx.sim_time_ns);

  auto message = toMessage(law);
  bus::put(message.m_body_Am2(), coils.m_B_Am2);
  message.active(law.active && !coils.window_active);
  message.header(bus::makeHeader(ctx, name()));
  command_.write(message);
  auto window = toMessage(coils.report);
  window.header(bus::makeHeader(ctx, name()));
  coil_window_.write(window);
}

UnloadingControllerNodeParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                                         bus::ConfigProblems& problems) {
  bus::ConfigProblems reported_by_dynamics_server;
  const auto plant = sim::readPlant(scenario, reported_by_dynamics_server);
  UnloadingControllerNodeParams node;
  CrossProductUnloadingParams& p = node.law;
  p.wheels = {plant.body.wheel_count, plant.body.wheel_axes_B, plant.body.wheel_inertia_kg_m2};
  p.max_dipole_Am2 = plant.torquer_max_dipole_Am2;
  auto r = scenario.componentParams(args.name, problems);
  r.read("enabled", p.enabled);
  r.read("gain_per_s", p.gain_per_s, "1/s");
  r.read("h_target_body_Nms", p.h_target_B_Nms, "N m s");
  r.read("h_start_Nms", p.h_start_Nms, "N m s");
  r.read("h_stop_Nms", p.h_stop_Nms, "N m s");
  r.read("min_field_T", p.min_field_T, "T");
  std::string source = "magnetometer";
  r.read("field_source", source);
  if (source == "s0_estimate") {
    node.field_source = FieldSource::kS0Estimate;
  } else if (source != "magnetometer") {
    r.problem("field_source", "must be magnetometer or s0_estimate, not \"" + source + "\"");
  }
  r.problems(p.validate());
  r.finish();
  return node;
}

}  // namespace flatsat::unloading_controller
