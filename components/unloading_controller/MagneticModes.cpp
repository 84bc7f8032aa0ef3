// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/MagneticModes.hpp"

#include <stdexcept>

#include "components/common/Validation.hpp"

namespace flatsat::unloading_controller {

namespace {

std::vector<std::string> prefixed(const std::string& prefix, std::vector<std::string> errors) {
  for (auto& e : errors) e = prefix + e;
  return errors;
}

BdotParams classic(BdotParams p) {
  p.omega_ref_B_rad_s.setZero();
  return p;
}

}  // namespace

std::optional<MagneticMode> magneticModeFromName(const std::string& name) {
  if (name == "unload") return MagneticMode::kUnload;
  if (name == "detumble") return MagneticMode::kDetumble;
  if (name == "spin_capture") return MagneticMode::kSpinCapture;
  return std::nullopt;
}

std::vector<std::string> MagneticModesParams::validate() const {
  std::vector<std::string> errors;
  append(errors, unload.validate());
  append(errors, prefixed("detumble.", detumble.validate()));
  append(errors, prefixed("spin_capture.", spin.validate()));
  require(errors, after_detumble != MagneticMode::kDetumble, "after_detumble", "must differ from detumble");
  requirePositive(errors, "handover_rate_rad_s", handover_rate_rad_s);
  requireNonNegative(errors, "handover_hold_s", handover_hold_s);
  if (aero) append(errors, prefixed("aero.", aero->validate()));
  return errors;
}

MagneticModes::MagneticModes(const Params& params)
    : params_(params),
      unload_(params.unload),
      detumble_(classic(params.detumble)),
      spin_(spinCaptureLaw(params.spin, params.unload.max_dipole_Am2)),
      mode_(params.initial_mode) {
  if (const auto errors = params_.validate(); !errors.empty()) {
    std::string message = "MagneticModesParams invalid:";
    for (const auto& e : errors) message += " " + e + ";";
    throw std::invalid_argument(message);
  }
  if (params_.aero) aero_.emplace(*params_.aero);
}

void MagneticModes::reset() { enter(params_.initial_mode); }

void MagneticModes::retune(const Params& params) {
  const Params& checked = validated(params, "MagneticModesParams");
  unload_.retune(checked.unload);
  params_ = checked;
}

void MagneticModes::command(MagneticMode mode) {
  if (mode != mode_) enter(mode);
}

void MagneticModes::enter(MagneticMode mode) {
  mode_ = mode;
  unload_.reset();
  detumble_.reset();
  spin_.reset();
  slow_since_ns_.reset();
}

MagneticModesOutput MagneticModes::step(const Input& in, std::int64_t t_ns) {
  Output out;
  out.mode = mode_;
  if (mode_ == MagneticMode::kUnload) {
    const auto u = unload_.step({in.wheel_speed_rad_s, in.b_B_T, in.b_valid}, t_ns);
    const double h = u.h_B_Nms.norm();
    out.m_B_Am2 = u.m_B_Am2;
    out.h_B_Nms = u.h_B_Nms;
    out.active = u.active;
    out.saturated = u.saturated;
    out.h_above_start = h > params_.unload.h_start_Nms;
    out.h_below_stop = h < params_.unload.h_stop_Nms;
    if (aero_) {
      // The law's torque in full: its coils alone give only the part ⟂ B, M × B = −k H⊥.
      if (u.active) out.c_demand_B_Nm = -params_.unload.gain_per_s * u.h_B_Nms;
      out.aero = aero_->step({out.c_demand_B_Nm, in.b_B_T, in.flap_scale_Nm}, t_ns);
      out.m_B_Am2 = out.aero->m_B_Am2;
      out.saturated = out.aero->coils_saturated || out.aero->flaps_saturated;
    }
    return out;
  }
  BdotInput law_in{in.b_B_T, in.b_valid, std::nullopt};
  if (mode_ == MagneticMode::kSpinCapture && params_.spin.field_turn == FieldTurn::kModel) {
    if (!in.onboard) return out;  // without the model the law's reference is wrong: coils off
    law_in.model = BdotModelField{in.onboard->b_N_T, in.onboard->orbit_normal_N_unit, params_.spin.spin_axis_B};
  }
  const auto b = (mode_ == MagneticMode::kDetumble ? detumble_ : spin_).step(law_in, t_ns);
  out.m_B_Am2 = b.m_B_Am2;
  out.active = b.active;
  out.saturated = b.saturated;
  out.rate_error_rad_s = b.rate_error_rad_s.value_or(0.0);
  if (mode_ != MagneticMode::kDetumble || !b.rate_error_rad_s) return out;

  out.rate_below_handover = *b.rate_error_rad_s < params_.handover_rate_rad_s;
  if (!out.rate_below_handover) {
    slow_since_ns_.reset();
  } else if (!slow_since_ns_) {
    slow_since_ns_ = t_ns;
  }
  const bool held = slow_since_ns_ && static_cast<double>(t_ns - *slow_since_ns_) * 1e-9 >= params_.handover_hold_s;
  if (held && params_.after_detumble) {
    enter(*params_.after_detumble);
    out.handover = true;
  }
  return out;
}

}  // namespace flatsat::unloading_controller
