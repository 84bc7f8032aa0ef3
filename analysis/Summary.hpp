// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "bus/Scenario.hpp"
#include "analysis/RunOutcome.hpp"

namespace flatsat::analysis {

/// The named metrics of a finished run, from its recording (truth is the
/// judge): pointing error after acquisition, stored wheel momentum, timing
/// and the recording digest.
nlohmann::ordered_json summarize(const bus::Scenario& scenario, const std::string& recording_path,
                                 const RunOutcome& launch);

/// The summary as an aligned two-column table.
std::string summaryTable(const nlohmann::ordered_json& summary);

}  // namespace flatsat::analysis
