// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/UnloadingControllerNode.hpp"

#include <optional>
#include <string>

#include <spdlog/spdlog.h>

#include "bus/Convert.hpp"
#include "components/Processes.hpp"
#include "components/common/onboard/ReferenceParams.hpp"
#include "sim/KeplerOrbit.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::unloading_controller {

namespace {

std::optional<CoilRequest> toRequest(const msg::CoilRequest& m) {
  if (m.request_id() == 0) return std::nullopt;
  return CoilRequest{m.request_id(),    bus::vec3(m.m_body_Am2()), m.quiet_s(), m.pulse_s(),
                     m.quiet_after_s(), m.law_pulse_min_Am2()};
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
  m.law_pulse(r.law_pulse);
  return m;
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

constexpr std::uint8_t kNoSplit = 255;  // FlapCmd.split: no aero section, flaps neutral

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

/// The `aero:` section (seed S2) and what the split needs to know of the flaps.
void readAero(bus::ParamReader& r, const vehicle::VehicleDescription& known, UnloadingControllerNodeParams& node) {
  if (!r.has("aero")) return;
  auto a = r.section("aero");
  if (!known.flaps.fitted) {
    a.problem("split", "spacecraft.flaps is not fitted: no flaps to split the torque with");
  }
  node.flaps = FlapKnowledge{known.flaps.plate_area_m2, known.flaps.lever_arm_m, known.atmosphere,
                             known.density_kg_m3};
  AeroAllocationParams p;
  p.max_dipole_Am2 = node.modes.unload.max_dipole_Am2;
  p.min_field_T = node.modes.unload.min_field_T;
  p.wings = known.flaps.wings;
  // The flaps' limit, and never past asin √(2/3), where a plate's roll torque peaks.
  p.flaps.max_angle_rad = std::min(known.flaps.max_angle_rad, p.flaps.max_angle_rad);
  std::string split = "magnetic_aero";
  a.read("split", split);
  if (const auto parsed = aeroSplitFromName(split)) {
    p.split = *parsed;
  } else {
    a.problem("split", "'" + split + "' is not magnetic_aero, flaps_only or drag_only");
  }
  a.read("max_angle_rad", p.flaps.max_angle_rad, "rad");
  std::string solver = "exact";
  a.read("flap_solver", solver);
  if (solver == "seed") {
    p.flaps.seed_closed_form = true;
  } else if (solver != "exact") {
    a.problem("flap_solver", "'" + solver + "' is neither exact nor seed (the closed forms IV-IX as they are)");
  }
  a.read("drag_only_angle_rad", p.drag_only_angle_rad, "rad");
  int failed = 0;
  a.read("failed_flap", failed);
  if (failed < 0 || failed > 4) {
    a.problem("failed_flap", "must be 1..4 (plate theta1..theta4), or 0 for none");
  } else if (failed > 0) {
    p.flaps.failed[static_cast<std::size_t>(failed - 1)] = true;
    if (p.flaps.seed_closed_form) {
      a.problem("flap_solver", "seed: the seed's closed forms have no replacement pattern for a failed plate");
    }
  }
  a.finish();
  node.modes.aero = p;
}

}  // namespace

UnloadingControllerNode::UnloadingControllerNode(bus::Bus& bus, bus::NodeOptions options,
                                                 const UnloadingControllerNodeParams& params)
    : Component(bus, std::move(options)),
      mode_commands_(bus, bus::topics::kUnloadingModeCmd, [this](const msg::ModeCmd& c) { receive(c); }),
      modes_(params.modes),
      param_commands_(
          bus, name(),
          {{"gain_per_s", [](MagneticModesParams& p) -> double& { return p.unload.gain_per_s; }},
           {"h_start_Nms", [](MagneticModesParams& p) -> double& { return p.unload.h_start_Nms; }},
           {"h_stop_Nms", [](MagneticModesParams& p) -> double& { return p.unload.h_stop_Nms; }},
           {"min_field_T", [](MagneticModesParams& p) -> double& { return p.unload.min_field_T; }},
           {"handover_rate_rad_s", [](MagneticModesParams& p) -> double& { return p.handover_rate_rad_s; }},
           {"handover_hold_s", [](MagneticModesParams& p) -> double& { return p.handover_hold_s; }}}),
      arbiter_(params.modes.unload.max_dipole_Am2),
      quiet_fraction_(params.quiet_fraction) {
  if (params.onboard) onboard_.emplace(*params.onboard);
  if (params.flaps) {
    flaps_ = params.flaps;
    if (flaps_->atmosphere) atmosphere_.emplace(*flaps_->atmosphere);
  }
  switch (params.field_source) {
    case FieldSource::kMagnetometer: magnetometer_ = &addInput(bus::topics::kMagnetometer); break;
    case FieldSource::kFieldFromMomentum:
      field_estimate_ = &addInput(bus::topics::kFieldEstimate);
      coil_request_ = &addInput(bus::topics::kCoilRequest);
      break;
    case FieldSource::kModelAttitude: attitude_ = &addInput(bus::topics::kAttitudeEstimate); break;
  }
}

void UnloadingControllerNode::receive(const msg::ModeCmd& command) {
  const auto mode = commandedMode(command);
  if (!mode) {
    const auto value = static_cast<std::int64_t>(command.mode());
    acks_.queue(command.command_id(), "mode", false,
                "mode " + std::to_string(value) + " is not unload, detumble or spin_capture");
    return;
  }
  std::lock_guard lock(mode_mutex_);
  requested_mode_ = *mode;
  mode_command_ids_.push_back(command.command_id());
}

void UnloadingControllerNode::step(const bus::StepContext& ctx) {
  {
    std::lock_guard lock(mode_mutex_);
    if (requested_mode_) {
      const std::string mode = unloading_controller::name(*requested_mode_);
      spdlog::info("{}: mode {} commanded", name(), mode);
      modes_.command(*requested_mode_);
      requested_mode_.reset();
      // Several commands between two steps: the last one is entered.
      for (std::size_t i = 0; i < mode_command_ids_.size(); ++i) {
        const bool last = i + 1 == mode_command_ids_.size();
        acks_.queue(mode_command_ids_[i], "mode", last,
                    last ? "entered " + mode : "superseded by a later mode command");
      }
      mode_command_ids_.clear();
    }
  }
  if (auto retuned = param_commands_.take(modes_.params(), [](const MagneticModesParams& p) { return p.validate(); },
                                          acks_, ctx)) {
    modes_.retune(*retuned);
  }
  acks_.publish(ctx, name());
  const auto reading = tach_.at(ctx.step);
  const auto tach = last_tach_.update(reading);
  MagneticModesInput in{bus::vec4(tach.wheel_speed_rad_s()), {}, false};
  if (onboard_) {
    const auto reference = onboard_->step(ctx.sim_time_ns);
    in.onboard = OnboardField{reference.b_N_T, reference.orbit_normal_N_unit};
    if (flaps_) in.flap_scale_Nm = flapScale_Nm(reference);
  }
  if (magnetometer_ != nullptr) {
    const auto field = magnetometer_->at(ctx.step);
    in.b_B_T = bus::vec3(field.b_body_T());
    in.b_valid = field.valid() && !field.saturated();
  } else if (field_estimate_ != nullptr) {
    const auto field = field_estimate_->at(ctx.step);
    in.b_B_T = bus::vec3(field.b_body_T());
    in.b_valid = field.valid();
  } else {
    // The model field in body axes through the estimated attitude: as good as the
    // two together, and never taken from an estimate that says it is not valid.
    const auto estimate = attitude_->at(ctx.step);
    const Eigen::Quaterniond q_NB = bus::quat(estimate.q_inertial_body()).normalized();
    in.b_B_T = q_NB.conjugate() * in.onboard->b_N_T;
    in.b_valid = estimate.valid() && in.b_B_T.allFinite();
  }
  const auto out = modes_.step(in, ctx.sim_time_ns);
  if (out.handover) {
    spdlog::info("{}: detumbled, {} from here", name(), unloading_controller::name(modes_.mode()));
  }
  std::optional<CoilRequest> request;
  if (coil_request_ != nullptr) request = toRequest(coil_request_->at(ctx.step));
  const auto coils = arbiter_.step(request, out.m_B_Am2, ctx.sim_time_ns);

  auto message = toMessage(out);
  bus::put(message.m_body_Am2(), coils.m_B_Am2);
  message.active(out.active && !coils.window_active);
  // A requested window (seed S0) is a known dipole over known times: never shortened.
  message.quiet_fraction(coils.window_active ? 0.0 : quiet_fraction_);
  bus::stamp(message.header(), ctx, name());
  command_.write(message);
  auto window = toMessage(coils.report);
  bus::stamp(window.header(), ctx, name());
  coil_window_.write(window);
  publishFlaps(ctx, in, out);
}

double UnloadingControllerNode::flapScale_Nm(const onboard::ReferenceVectors& reference) const {
  const double speed2 = sim::velocityThroughAir_N_m_s(reference.r_N_m, reference.v_N_m_s).squaredNorm();
  const double density = atmosphere_ ? atmosphere_->density_kg_m3(reference.r_N_m, reference.sun_N_unit)
                                     : flaps_->density_kg_m3;
  return 2.0 * density * flaps_->plate_area_m2 * speed2 * flaps_->lever_arm_m;
}

void UnloadingControllerNode::publishFlaps(const bus::StepContext& ctx, const MagneticModesInput& in,
                                           const MagneticModesOutput& out) {
  msg::FlapCmd m;
  m.split(kNoSplit);
  if (out.aero) {
    const AeroAllocationOutput& a = *out.aero;
    bus::put(m.theta_rad(), a.flaps.theta_rad);
    m.split(static_cast<std::uint8_t>(modes_.params().aero->split));
    m.branch(static_cast<std::uint8_t>(a.flaps.branch));
    m.replaced(a.flaps.replaced);
    bus::put(m.c_demand_body_Nm(), out.c_demand_B_Nm);
    bus::put(m.c_aero_body_Nm(), a.c_aero_B_Nm);
    bus::put(m.c_magnetic_body_Nm(), a.c_magnetic_B_Nm);
    m.delivered(a.delivered);
    m.flaps_saturated(a.flaps_saturated);
  }
  bus::put(m.b_body_T(), in.b_B_T);
  m.flap_scale_Nm(in.flap_scale_Nm);
  bus::stamp(m.header(), ctx, name());
  flap_cmd_.write(m);
}

UnloadingControllerNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                         const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  const vehicle::VehicleDescription& known = vehicle.onboard;  // flight software sees only this
  UnloadingControllerNodeParams node;
  MagneticModesParams& p = node.modes;
  CrossProductUnloadingParams& u = p.unload;
  u.wheels = wheelGeometryOf(known.body);
  u.max_dipole_Am2 = known.torquer_max_dipole_Am2;
  p.detumble.max_dipole_Am2 = known.torquer_max_dipole_Am2;
  if (known.orbit.validate().empty()) p.spin.orbit_rate_rad_s = sim::KeplerOrbit(known.orbit).meanMotion_rad_s();

  auto r = scenario.componentParams(args.name, problems);
  vehicle::refuseMovedKeys(r, vehicle::kMovedReferenceKeys);
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
  std::string law = "corrected";
  s.read("law", law);
  if (law == "seed") {
    p.spin.law = SpinLaw::kSeed;
    for (const char* key : {"spin_rate_rad_s", "field_turn_per_orbit_rate"}) {
      if (s.has(key)) s.problem(key, "the seed's law (law: seed) has no requested spin rate and no field-turn factor");
    }
  } else if (law != "corrected") {
    s.problem("law", "'" + law + "' is neither corrected nor seed");
  }
  std::string field_turn = "orbit_rate";
  s.read("field_turn", field_turn);
  if (field_turn == "model") {
    p.spin.field_turn = FieldTurn::kModel;
  } else if (field_turn != "orbit_rate") {
    s.problem("field_turn", "'" + field_turn + "' is neither orbit_rate nor model");
  }
  s.finish();
  const auto reference = onboard::referenceModelOf(known, onboard::readFieldNodeSpacing(r));
  readAero(r, known, node);

  std::string source = "magnetometer";
  r.read("field_source", source);
  r.read("quiet_fraction", node.quiet_fraction, "-");
  if (!(node.quiet_fraction >= 0.0 && node.quiet_fraction < 1.0)) {
    r.problem("quiet_fraction", "must be in [0, 1)");
  }
  if (source == "s0_estimate") {
    node.field_source = FieldSource::kFieldFromMomentum;
  } else if (source == "model_attitude") {
    node.field_source = FieldSource::kModelAttitude;
  } else if (source != "magnetometer") {
    r.problem("field_source", "must be magnetometer, s0_estimate or model_attitude, not \"" + source + "\"");
  }
  if (p.spin.field_turn == FieldTurn::kModel || node.field_source == FieldSource::kModelAttitude || p.aero) {
    node.onboard = reference;
  }
  r.problems(p.validate());
  if (node.onboard) r.problems(node.onboard->validate());
  r.finish();
  return node;
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<UnloadingControllerNode>(argc, argv, "unloading_controller", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::unloading_controller
