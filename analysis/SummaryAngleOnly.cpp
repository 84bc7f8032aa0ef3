// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryAngleOnly.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "bus/Convert.hpp"
#include "components/Registry.hpp"
#include "components/thruster_sequencer/ThrusterSequencerNode.hpp"
#include "analysis/Conventions.hpp"

namespace flatsat::analysis {

namespace {

thruster_sequencer::AngleOnlyLimitCycleOutput decision(const msg::ThrusterCmd& m) {
  thruster_sequencer::AngleOnlyLimitCycleOutput out;
  out.pulse = m.pulse();
  out.phase = static_cast<thruster_sequencer::LimitCyclePhase>(m.phase());
  out.correction_count = m.correction_count();
  out.braking_count = m.braking_count();
  out.braking_remaining = m.braking_remaining();
  out.braking = m.braking();
  return out;
}

}  // namespace

ThrusterSequencerFigures::ThrusterSequencerFigures(const bus::Scenario& scenario, const vehicle::Vehicle& craft)
    : step_s_(scenario.step_s) {
  if (!scenario.hasComponent("thruster_sequencer")) return;
  bus::ConfigProblems ignored;  // the scenario was checked before the run
  const auto sequencer = thruster_sequencer::readParams(scenario, craft, {scenario.file, "thruster_sequencer", ""}, ignored);
  if (sequencer.mode != thruster_sequencer::ThrusterSequencerParams::Mode::kAngleOnly) return;
  params_ = sequencer.angle_only;
  if (const auto reach = angleOnlyBrakingReach(scenario, craft)) {
    reach_["t2_condition_holds"] = reach->holds;
    reach_["t2_condition"] = {{"drift_rate_deg_s", reach->drift_rate_rad_s * kRadToDeg},
                              {"braking_pulses", reach->braking_pulses},
                              {"travel_deg", reach->travel_rad * kRadToDeg},
                              {"room_deg", reach->room_rad * kRadToDeg},
                              {"longest_braking_interval_s", reach->longest_interval_s}};
  }
}

void ThrusterSequencerFigures::addCmd(std::uint64_t step, const ThrusterCmdSample& cmd) {
  if (!params_) return;
  tally_.add(decision(cmd));
  if (cmd.braking() && cmd.pulse() != 0) {
    if (cmd.braking_count() - cmd.braking_remaining() == 1) brakings_.emplace_back(step, step);
    if (!brakings_.empty()) brakings_.back().second = step;
  }
  delta_rate_rad_s_ = cmd.pulse_delta_rate_rad_s();
  const auto& on = cmd.on_time_s();
  const bool any = std::any_of(on.begin(), on.end(), [](double t) { return t > 0.0; });
  if (any) last_pulse_end_s_ = static_cast<double>(step + 1) * step_s_;
}

void ThrusterSequencerFigures::addTruth(std::uint64_t step, const TruthSample& truth) {
  if (!params_) return;
  const auto& cycle = params_->cycle;
  const double t = static_cast<double>(truth.header().sim_time_ns()) * 1e-9;
  angle_ = thruster_sequencer::angleAboutAxis_rad(bus::vec3(truth.sun_body_unit()), params_->boresight_B,
                                                  params_->axis_B);
  rate_ = params_->axis_B.dot(bus::vec3(truth.w_body_rad_s()));
  if (angle_ <= cycle.upper_limit_rad && angle_ >= cycle.lower_limit_rad) return;
  settle_s_ = t + step_s_;
  if (!outside_.empty() && outside_.back().second + 1 == step) {
    outside_.back().second = step;
  } else {
    outside_.emplace_back(step, step);
  }
}

void ThrusterSequencerFigures::summarize(nlohmann::ordered_json& summary) const {
  if (!params_) return;
  // A braking's last pulse acts over the step after it.
  std::int64_t left_range = 0;
  for (const auto& [first, last] : brakings_) {
    left_range += std::any_of(outside_.begin(), outside_.end(),
                              [&](const auto& out) { return out.second > first && out.first <= last + 1; });
  }
  summary["correction_counts"] = tally_.correction_counts;
  summary["braking_counts"] = tally_.braking_counts;
  summary["total_pulses"] = tally_.total;
  summary["pulse_delta_rate_deg_s"] = delta_rate_rad_s_ * kRadToDeg;
  summary["final_angle_deg"] = angle_ * kRadToDeg;
  summary["final_rate_deg_s"] = rate_ * kRadToDeg;
  summary["settle_time_s"] = std::max(settle_s_, last_pulse_end_s_);
  summary["brakings_left_range"] = left_range;
  for (const auto& [key, value] : reach_.items()) summary[key] = value;
}

}  // namespace flatsat::analysis
