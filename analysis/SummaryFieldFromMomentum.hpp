// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <nlohmann/json.hpp>

#include "bus/Recording.hpp"
#include "bus/Scenario.hpp"

namespace flatsat::analysis {

/// Seed S0's metrics, when the run recorded a field estimate: field error (% of
/// |B|) and roll error about the Sun line, RMS over the steps with a valid estimate,
/// judged against the recorded truth; windows solved and failed.
void addFieldFromMomentumMetrics(nlohmann::ordered_json& summary, const bus::Scenario& scenario,
                  const bus::Recording& recording);

}  // namespace flatsat::analysis
