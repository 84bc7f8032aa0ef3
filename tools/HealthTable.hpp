// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <map>
#include <mutex>
#include <string>

#include <nlohmann/json.hpp>

#include "tools/ToolBus.hpp"

namespace flatsat::tools {

using HealthDef = std::remove_cvref_t<decltype(bus::topics::kHealth)>;

/// A component's newest health and the writer it came from (gone: its participant left).
struct HealthEntry {
  msg::Health health;
  Guid writer;
  bool writer_alive = true;  ///< false: its health writer's liveliness lapsed (bus::kHealthLease)
};

/// One row per component: state, steps done, lag (steps behind the component furthest
/// ahead, at their last health), overruns (deadline misses), stale inputs, drops, refusals,
/// inputs' deadlines missed, age of the last health, alive, late (running, alive, and its
/// health older than bus::kHealthLate), message (`flatsat health --json`; `flatsat foxglove` turns it into status messages).
/// Each component's newest health into `entries` (under `mutex`) as it
/// arrives, its writer marked dead when its liveliness lapses.
class HealthWatcher {
 public:
  HealthWatcher(ToolBus& tool_bus, std::mutex& mutex, std::map<std::string, HealthEntry>& entries);

 private:
  bus::Reader<HealthDef> reader_;
};

nlohmann::ordered_json healthTable(const std::map<std::string, HealthEntry>& entries, const ToolBus& tool_bus);

}  // namespace flatsat::tools
