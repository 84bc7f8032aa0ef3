// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <nlohmann/json.hpp>

#include "bus/Recording.hpp"
#include "bus/Scenario.hpp"

namespace flatsat::analysis {

/// Adds the estimator's accuracy and consistency against the recorded truth, from the
/// acquisition time on, when the estimator publishes a covariance (MEKF):
/// - attitude_error_deg_3sigma: 3·RMS of the attitude error angle in full sunlight;
/// - nees_in_bounds_fraction: share of valid estimates whose attitude NEES δθᵀP⁻¹δθ lies in
///   the two-sided 95 % bounds of χ²_3, [0.2158, 9.3484];
/// - estimator_measurements_rejected: the innovation gate's count at the end.
void summarizeEstimator(const bus::Scenario& scenario, const bus::Recording& recording,
                        nlohmann::ordered_json& summary);

}  // namespace flatsat::analysis
