// SPDX-License-Identifier: Apache-2.0
#include "components/thruster_sequencer/AngleOnlyLimitCycle.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "components/common/Validation.hpp"

namespace flatsat::thruster_sequencer {

namespace {

std::int64_t toNanoseconds(double seconds) { return std::llround(seconds * 1e9); }

}  // namespace

std::vector<std::string> AngleOnlyLimitCycleParams::validate() const {
  std::vector<std::string> errors;
  require(errors, std::isfinite(target_rad), "target_rad", "must be finite");
  require(errors, lower_limit_rad < target_rad && std::isfinite(lower_limit_rad), "lower_limit_rad",
          "must be finite and < target_rad");
  require(errors, upper_limit_rad > target_rad && std::isfinite(upper_limit_rad), "upper_limit_rad",
          "must be finite and > target_rad");
  requirePositive(errors, "correction_interval_s", correction_interval_s);
  requirePositive(errors, "braking_interval_s", braking_interval_s);
  require(errors, braking_interval_s < correction_interval_s, "braking_interval_s",
          "must be < correction_interval_s (T2 < T1)");
  return errors;
}

BrakingReach brakingReach(const AngleOnlyLimitCycleParams& cycle, const BrakingDrift& drift) {
  const double dw = std::abs(drift.pulse_delta_rate_rad_s);
  BrakingReach reach;
  reach.drift_rate_rad_s = std::max(std::abs(drift.drift_rate_rad_s), dw);
  reach.braking_pulses = static_cast<int>(std::ceil(reach.drift_rate_rad_s / dw - 1e-9));
  double coasting = 0.0;  // [rad/s·s/T2] Σ (ω − kδω)⁺: the travel per second of T2
  for (int k = 1; k < reach.braking_pulses; ++k) coasting += std::max(reach.drift_rate_rad_s - k * dw, 0.0);
  const double fixed = reach.drift_rate_rad_s * drift.sample_period_s + reach.braking_pulses * dw * drift.pulse_on_time_s / 2.0;
  reach.travel_rad = fixed + cycle.braking_interval_s * coasting;
  reach.room_rad = std::min(cycle.upper_limit_rad - cycle.target_rad, cycle.target_rad - cycle.lower_limit_rad);
  reach.longest_interval_s = coasting > 0.0 ? std::max((reach.room_rad - fixed) / coasting, 0.0)
                                            : (fixed <= reach.room_rad ? cycle.correction_interval_s : 0.0);
  reach.holds = reach.travel_rad <= reach.room_rad;
  return reach;
}

AngleOnlyLimitCycle::AngleOnlyLimitCycle(const Params& params)
    : params_(params),
      correction_interval_ns_(toNanoseconds(params.correction_interval_s)),
      braking_interval_ns_(toNanoseconds(params.braking_interval_s)) {
  if (const auto errors = params_.validate(); !errors.empty()) {
    std::string message = "AngleOnlyLimitCycleParams invalid:";
    for (const auto& e : errors) message += " " + e + ";";
    throw std::invalid_argument(message);
  }
}

void AngleOnlyLimitCycle::reset() {
  phase_ = LimitCyclePhase::kAcquiring;
  side_ = correction_count_ = braking_count_ = braking_remaining_ = 0;
  fired_ = false;
  last_pulse_ns_ = 0;
}

void AngleOnlyLimitCycle::restore(const State& state) {
  phase_ = state.phase;
  side_ = state.side;
  correction_count_ = state.correction_count;
  braking_count_ = state.braking_count;
  braking_remaining_ = state.braking_remaining;
  fired_ = state.fired;
  last_pulse_ns_ = state.last_pulse_ns;
}

bool AngleOnlyLimitCycle::pulseDue(std::int64_t t_ns, std::int64_t interval_ns) const {
  return !fired_ || t_ns - last_pulse_ns_ >= interval_ns;
}

AngleOnlyLimitCycleOutput AngleOnlyLimitCycle::report(int pulse, bool braking) const {
  return {pulse, phase_, correction_count_, braking_count_, braking_remaining_, braking};
}

AngleOnlyLimitCycleOutput AngleOnlyLimitCycle::fire(int direction, bool braking, std::int64_t t_ns) {
  fired_ = true;
  last_pulse_ns_ = t_ns;
  return report(direction, braking);
}

void PulseTally::add(const AngleOnlyLimitCycleOutput& out) {
  if (out.pulse == 0) return;
  ++total;
  if (out.braking) {
    const int fired = out.braking_count - out.braking_remaining;
    if (fired == 1 || braking_counts.empty()) braking_counts.push_back(0);
    braking_counts.back() = fired;
  } else {
    if (out.correction_count == 1 || correction_counts.empty()) correction_counts.push_back(0);
    correction_counts.back() = out.correction_count;
  }
}

AngleOnlyLimitCycleOutput AngleOnlyLimitCycle::step(const Input& in, std::int64_t t_ns) {
  if (!in.valid || !std::isfinite(in.angle_rad)) return report(0);

  if (phase_ == LimitCyclePhase::kBraking) {
    if (!pulseDue(t_ns, braking_interval_ns_)) return report(0);
    if (--braking_remaining_ == 0) phase_ = LimitCyclePhase::kHolding;
    return fire(side_, true, t_ns);  // the angle comes from side_, so the motion is toward −side_
  }

  const double angle = in.angle_rad;
  if (angle > params_.upper_limit_rad || angle < params_.lower_limit_rad) {
    const int side = angle > params_.upper_limit_rad ? 1 : -1;
    if (phase_ != LimitCyclePhase::kCorrecting || side != side_) {
      phase_ = LimitCyclePhase::kCorrecting;
      side_ = side;
      correction_count_ = 0;
      fired_ = false;
    }
    if (!pulseDue(t_ns, correction_interval_ns_)) return report(0);
    ++correction_count_;
    return fire(-side_, false, t_ns);
  }

  if (phase_ == LimitCyclePhase::kCorrecting) phase_ = LimitCyclePhase::kCoasting;
  if (phase_ != LimitCyclePhase::kCoasting || (angle - params_.target_rad) * side_ > 0.0) {
    return report(0);
  }
  // Zero cross after a correction: claim 3's braking amount, ⌊n/2⌋ (integer division).
  braking_count_ = correction_count_ / 2;
  braking_remaining_ = braking_count_;
  if (braking_remaining_ == 0) {
    phase_ = LimitCyclePhase::kHolding;
    return report(0);
  }
  phase_ = --braking_remaining_ == 0 ? LimitCyclePhase::kHolding : LimitCyclePhase::kBraking;
  fired_ = false;
  return fire(side_, true, t_ns);
}

}  // namespace flatsat::thruster_sequencer
