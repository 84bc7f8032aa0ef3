// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <nlohmann/json.hpp>

#include "bus/Recording.hpp"
#include "bus/Scenario.hpp"

namespace flatsat::analysis {

/// Seed S1's figures when the rig has a thruster_sequencer in mode angle_only: correction_counts and
/// braking_counts (lists, in order), total_pulses, pulse_delta_rate_deg_s, final_angle_deg,
/// final_rate_deg_s (about the controlled axis, from the truth) and settle_time_s (from
/// then on inside the limit range with no pulse); brakings_left_range (brakings during which the
/// true angle left [A2, A3]); t2_condition_holds and t2_condition (angleOnlyBrakingReach: the
/// seed's condition on T2 for the run's start, with its figures). Nothing otherwise.
void summarizeThrusterSequencer(const bus::Scenario& scenario, const bus::Recording& recording,
                                nlohmann::ordered_json& summary);

}  // namespace flatsat::analysis
