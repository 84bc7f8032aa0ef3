// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <nlohmann/json.hpp>

#include "bus/Recording.hpp"
#include "bus/Scenario.hpp"

namespace flatsat::analysis {

/// Detumble and spin-capture keys of summary.json, from the recorded
/// truth, when the unloading controller starts in detumble or spin_capture:
/// rate_deg_s_final, time_to_detumble_s (null: not below 0.2 deg/s at the end),
/// coil_duty, and with spin capture spin_axis_error_deg, spin_rate_error_pct,
/// time_to_capture_s (MagneticMetrics). Other scenarios: nothing added.
void summarizeMagnetic(const bus::Scenario& scenario, const bus::Recording& recording,
                       nlohmann::ordered_json& summary);

}  // namespace flatsat::analysis
