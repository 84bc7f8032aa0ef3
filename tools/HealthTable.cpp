// SPDX-License-Identifier: Apache-2.0
#include "tools/HealthTable.hpp"

#include <algorithm>
#include <chrono>

#include "bus/Qos.hpp"
#include "bus/Stamp.hpp"

namespace flatsat::tools {

namespace {

/// Deadline misses of a paced rig, when the Health type carries them.
template <class H>
std::uint64_t overruns(const H& h) {
  if constexpr (requires { h.overruns(); }) {
    return h.overruns();
  } else {
    return 0;
  }
}
template <class H>
std::uint64_t staleInputs(const H& h) {
  if constexpr (requires { h.stale_inputs(); }) {
    return h.stale_inputs();
  } else {
    return 0;
  }
}

double ageSeconds(const msg::Health& h) {
  const auto now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                          std::chrono::system_clock::now().time_since_epoch())
                          .count();
  return static_cast<double>(now_ns - static_cast<std::int64_t>(h.wall_time_ns())) * 1e-9;
}

}  // namespace

HealthWatcher::HealthWatcher(ToolBus& tool_bus, std::mutex& mutex, std::map<std::string, HealthEntry>& entries)
    : reader_(
          tool_bus.bus(), bus::topics::kHealth,
          [&mutex, &entries](const msg::Health& h, const Arrival& a) {
            std::lock_guard lock(mutex);
            entries[bus::text(h.header().source())] = {h, a.writer, true};
          },
          [&mutex, &entries](const Guid& writer, bool alive) {  // a killed component shows within bus::kHealthLease
            std::lock_guard lock(mutex);
            for (auto& [name, entry] : entries) {
              if (entry.writer == writer) entry.writer_alive = alive;
            }
          }) {}

nlohmann::ordered_json healthTable(const std::map<std::string, HealthEntry>& entries, const ToolBus& tool_bus) {
  const auto participants = tool_bus.participants();
  auto rows = nlohmann::ordered_json::array();
  for (const auto& [name, e] : entries) {
    const auto p = participants.find(e.writer.guidPrefix);
    const bool alive = e.writer_alive && p != participants.end() && p->second.alive;
    const double age_s = ageSeconds(e.health);
    rows.push_back({{"component", name},
                    {"state", msg::toJson(e.health.state())},
                    {"steps_done", e.health.steps_done()},
                    // Both of the moment the component stamped its health: healths of
                    // different moments (a second apart) are not comparable.
                    {"lag_steps", e.health.step_granted() - std::min(e.health.step_reached(), e.health.step_granted())},
                    {"overruns", overruns(e.health)},
                    {"stale_inputs", staleInputs(e.health)},
                    {"samples_dropped", e.health.samples_dropped()},
                    {"commands_refused", e.health.commands_refused()},
                    {"deadlines_missed", e.health.deadlines_missed()},
                    {"age_s", age_s},
                    {"alive", alive},
                    {"late", alive && e.health.state() == msg::ComponentState::RUNNING &&
                                 age_s > std::chrono::duration<double>(bus::kHealthLate).count()},
                    {"message", bus::text(e.health.message())}});
  }
  return rows;
}

}  // namespace flatsat::tools
