// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/TruthSample.hpp"
#include "bus/Scenario.hpp"
#include "components/thruster_sequencer/ThrusterSequencerNode.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::analysis {

/// Seed S1's figures when the rig has a thruster_sequencer in mode angle_only: correction_counts and
/// braking_counts (lists, in order), total_pulses, pulse_delta_rate_deg_s, final_angle_deg,
/// final_rate_deg_s (about the controlled axis, from the truth) and settle_time_s (from
/// then on inside the limit range with no pulse); brakings_left_range (brakings during which the
/// true angle left [A2, A3]); t2_condition_holds and t2_condition (angleOnlyBrakingReach: the
/// seed's condition on T2 for the run's start, with its figures). Nothing otherwise.
class ThrusterSequencerFigures {
 public:
  ThrusterSequencerFigures(const bus::Scenario& scenario, const vehicle::Vehicle& craft);
  void addCmd(std::uint64_t step, const ThrusterCmdSample& cmd);
  void addTruth(std::uint64_t step, const TruthSample& truth);
  void summarize(nlohmann::ordered_json& summary) const;

 private:
  std::optional<thruster_sequencer::AngleOnlySequencerParams> params_;  // none: not an angle-only rig
  double step_s_ = 0.0;
  nlohmann::ordered_json reach_;  // the T2 condition's keys, computed with the scenario
  thruster_sequencer::PulseTally tally_;
  double last_pulse_end_s_ = 0.0, delta_rate_rad_s_ = 0.0;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> brakings_;  // [-] steps of each braking's first and last pulse
  double angle_ = 0.0, rate_ = 0.0, settle_s_ = 0.0;
  /// [-] the steps, first to last, over which the true angle was outside the limits:
  /// the brakings are judged against them at the end, when all are known.
  std::vector<std::pair<std::uint64_t, std::uint64_t>> outside_;
};

}  // namespace flatsat::analysis
