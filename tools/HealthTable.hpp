// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "tools/ToolBus.hpp"

namespace flatsat::tools {

using HealthDef = std::remove_cvref_t<decltype(bus::topics::kHealth)>;

/// A component's newest health and the writer it came from (gone: its participant left).
struct HealthEntry {
  msg::Health health;
  Guid writer;
};

/// One row per component: state, steps done, lag (steps behind the component furthest
/// ahead, at their last health), overruns (deadline misses), stale inputs, drops, refusals,
/// age of the last health, alive, message (`flatsat health --json`, the web view).
nlohmann::ordered_json healthTable(const std::map<std::string, HealthEntry>& entries, const ToolBus& tool_bus);

}  // namespace flatsat::tools
