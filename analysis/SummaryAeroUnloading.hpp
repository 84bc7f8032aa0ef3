// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <nlohmann/json.hpp>

#include "bus/Recording.hpp"
#include "bus/Scenario.hpp"

namespace flatsat::analysis {

/// Seed S2 keys of summary.json, when the unloading controller splits its
/// torque with the flaps (`aero:`), from flatsat/flap_cmd and the truth at the same step:
///  - aero_torque_ratio: Σ|flap torque (plant)| / Σ|C·B̂|, C the torque the law asked for and
///    B the plant's field: the flaps' torque against the component of C along B. No flap
///    torque in the flaps' plane (roll–yaw, or roll–pitch with the wings along z) that
///    completes C can go below aero_torque_ratio_least, Σ|C·B|/|B in that plane| / Σ|C·B̂|,
///    1 when B lies in the plane.
///  - drag_ratio: the flaps' drag over the run, K Σ|sin θi|³ summed over the steps, against
///    what the flaps-alone split (their plane's part from the flaps, AeroSplit::kFlapsOnly) would
///    have needed for the same demands, field and air: < 1 is less drag than flaps alone.
///  - flap_drag_N_mean: the plant's flap force against the air's velocity, mean over the run.
///  - torque_delivered_mean: mean share of the demand delivered (limits scale it down).
///  - flap_torque_error_pct_rms (split magnetic_aero): the flaps' share of the demand
///    (eq. II, on the field the law used, times the share delivered) against K·(c_ax, c_az)
///    of the commanded angles by the seed's shapes: the flap solver's own error, RMS over
///    the steps with a demand.
void summarizeAeroUnloading(const bus::Scenario& scenario, const bus::Recording& recording, nlohmann::ordered_json& summary);

}  // namespace flatsat::analysis
