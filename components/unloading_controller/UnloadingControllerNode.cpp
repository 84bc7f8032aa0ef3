// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/UnloadingControllerNode.hpp"

#include <spdlog/spdlog.h>

#include "bus/Convert.hpp"
#include "sim/DynamicsServerParams.hpp"
#include "sim/KeplerOrbit.hpp"

namespace flatsat::unloading_controller {

namespace {

MagneticModesInput toInput(const msg::WheelTachReading& tach, const msg::MagnetometerReading& field) {
  return {bus::vec4(tach.wheel_speed_rad_s()), bus::vec3(field.b_body_T()),
          field.valid() && !field.saturated()};
}

msg::DipoleCmd toMessage(const MagneticModesOutput& out) {
  msg::DipoleCmd m;
  bus::put(m.m_body_Am2(), out.m_B_Am2);
  bus::put(m.h_wheels_body_Nms(), out.h_B_Nms);
  m.active(out.active);
  m.saturated(out.saturated);
  m.mode(static_cast<std::uint8_t>(out.mode));
  m.h_above_start(out.h_above_start);
  m.h_below_stop(out.h_below_stop);
  m.rate_error_rad_s(out.rate_error_rad_s);
  m.rate_below_handover(out.rate_below_handover);
  m.handover(out.handover);
  return m;
}

const char* name(MagneticMode mode) {
  switch (mode) {
    case MagneticMode::kUnload: return "unload";
    case MagneticMode::kDetumble: return "detumble";
    case MagneticMode::kSpinCapture: return "spin_capture";
  }
  return "?";
}

static_assert(static_cast<int>(msg::MAGNETIC_UNLOAD) == static_cast<int>(MagneticMode::kUnload) &&
              static_cast<int>(msg::MAGNETIC_DETUMBLE) == static_cast<int>(MagneticMode::kDetumble) &&
              static_cast<int>(msg::MAGNETIC_SPIN_CAPTURE) == static_cast<int>(MagneticMode::kSpinCapture));

void readMode(bus::ParamReader& r, const std::string& key, std::optional<MagneticMode>& mode) {
  std::string text;
  r.read(key, text);
  if (!r.has(key)) return;
  mode = magneticModeFromName(text);
  if (!mode) r.problem(key, "'" + text + "' is not unload, detumble or spin_capture");
}

}  // namespace

UnloadingControllerNode::UnloadingControllerNode(bus::Bus& bus, bus::NodeOptions options,
                                                 const MagneticModesParams& params)
    : Component(bus, std::move(options)),
      mode_commands_(bus, bus::topics::kUnloadingModeCmd, [this](const msg::ModeCmd& c) { receive(c); }),
      modes_(params) {}

void UnloadingControllerNode::receive(const msg::ModeCmd& command) {
  const int mode = static_cast<int>(command.mode());
  if (mode < 0 || mode > static_cast<int>(MagneticMode::kSpinCapture)) {
    spdlog::warn("{}: mode command {} from {} refused", name(), mode, bus::text(command.header().source()));
    return;
  }
  std::lock_guard lock(mode_mutex_);
  requested_mode_ = static_cast<MagneticMode>(mode);
}

void UnloadingControllerNode::step(const bus::StepContext& ctx) {
  {
    std::lock_guard lock(mode_mutex_);
    if (requested_mode_) {
      spdlog::info("{}: mode {} commanded", name(), unloading_controller::name(*requested_mode_));
      modes_.command(*requested_mode_);
      requested_mode_.reset();
    }
  }
  const auto& tach = last_tach_.update(tach_.at(ctx.step));
  const auto out = modes_.step(toInput(tach, field_.at(ctx.step)), ctx.sim_time_ns);
  if (out.handover) {
    spdlog::info("{}: detumbled, {} from here", name(), unloading_controller::name(modes_.mode()));
  }
  auto message = toMessage(out);
  message.header(bus::makeHeader(ctx, name()));
  command_.write(message);
}

MagneticModesParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                               bus::ConfigProblems& problems) {
  bus::ConfigProblems reported_by_dynamics_server;
  const auto plant = sim::readPlant(scenario, reported_by_dynamics_server);
  MagneticModesParams p;
  CrossProductUnloadingParams& u = p.unload;
  u.wheels = {plant.body.wheel_count, plant.body.wheel_axes_B, plant.body.wheel_inertia_kg_m2};
  u.max_dipole_Am2 = plant.torquer_max_dipole_Am2;
  p.detumble.max_dipole_Am2 = plant.torquer_max_dipole_Am2;
  if (plant.orbit.validate().empty()) p.spin.orbit_rate_rad_s = sim::KeplerOrbit(plant.orbit).meanMotion_rad_s();

  auto r = scenario.componentParams(args.name, problems);
  r.read("enabled", u.enabled);
  r.read("gain_per_s", u.gain_per_s, "1/s");
  r.read("h_target_body_Nms", u.h_target_B_Nms, "N m s");
  r.read("h_start_Nms", u.h_start_Nms, "N m s");
  r.read("h_stop_Nms", u.h_stop_Nms, "N m s");
  r.read("min_field_T", u.min_field_T, "T");
  p.detumble.min_field_T = u.min_field_T;
  std::optional<MagneticMode> initial;
  readMode(r, "mode", initial);
  p.initial_mode = initial.value_or(MagneticMode::kUnload);
  readMode(r, "after_detumble", p.after_detumble);
  r.read("handover_rate_rad_s", p.handover_rate_rad_s, "rad/s");
  r.read("handover_hold_s", p.handover_hold_s, "s");

  auto d = r.section("detumble");
  std::string shape = "bang_bang";
  d.read("shape", shape);
  if (shape == "proportional") {
    p.detumble.shape = BdotShape::kProportional;
  } else if (shape != "bang_bang") {
    d.problem("shape", "'" + shape + "' is neither bang_bang nor proportional");
  }
  d.read("gain_Am2_s_per_T", p.detumble.gain_Am2_s_per_T, "A m^2 s/T");
  d.read("filter_time_constant_s", p.detumble.filter_time_constant_s, "s");
  d.read("deadband_rad_s", p.detumble.deadband_rad_s, "rad/s");
  d.read("max_sample_gap_s", p.detumble.max_sample_gap_s, "s");
  d.finish();

  auto s = r.section("spin_capture");
  s.read("spin_axis_body", p.spin.spin_axis_B, "-");
  s.read("spin_rate_rad_s", p.spin.spin_rate_rad_s, "rad/s");
  s.read("field_turn_per_orbit_rate", p.spin.field_turn_per_orbit_rate, "-");
  s.finish();

  r.problems(p.validate());
  r.finish();
  return p;
}

}  // namespace flatsat::unloading_controller
