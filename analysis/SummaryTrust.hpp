// SPDX-License-Identifier: Apache-2.0
#pragma once
// The summary's verdicts on the run itself (architecture, "Trust on the
// bus"): whether it ran to its last step, and what its consumers refused.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bus/Recording.hpp"

namespace flatsat::analysis {

/// `completed` (the recording holds the grant of the run's final step, as the
/// time master stamped it; a decimated one its last recorded multiple) and
/// `end_reason` ("completed", or where the recording ends).
void addCompletion(nlohmann::ordered_json& summary, const bus::Recording& recording);

/// From each component's last recorded health: `samples_rejected` (and by
/// topic, over every component), `commands_clamped`, and `intruders`: the
/// writers seen on a topic that the scenario does not declare as its
/// producer (the recorder's fault events of kind "intruder", with each
/// writer's GUID and participant in `intruder_writers`; at least as many as
/// any one component counted).
void addTrustMetrics(nlohmann::ordered_json& summary, const bus::Recording& recording);

}  // namespace flatsat::analysis
