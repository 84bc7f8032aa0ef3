// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryTrust.hpp"

#include <algorithm>

#include "bus/Stamp.hpp"

namespace flatsat::analysis {

void BusFigures::addGrant(std::uint64_t step, const GrantSample& grant) {
  if (granted_ && step < last_grant_) return;
  granted_ = true;
  last_grant_ = step;
  final_step_ = grant.final_step();
}

void BusFigures::addHealth(std::uint64_t step, const std::string& source, const HealthSample& health) {
  const auto [it, first] = health_.try_emplace(source);
  LastHealth& last = it->second;
  if (!first && step < last.step) return;
  last = {step,
          health.stale_inputs(),
          health.overruns(),
          health.deadlines_missed(),
          health.samples_dropped(),
          health.commands_refused(),
          health.samples_rejected(),
          health.commands_clamped(),
          health.intruders(),
          {}};
  for (const auto& slot : health.rejected_by_topic()) {
    if (slot.count() > 0) last.rejected_by_topic[bus::text(slot.topic())] = slot.count();
  }
  if (health.tick_late_us_max() > 0 && step >= tick_late_step_) {
    tick_late_step_ = step;
    tick_late_ = {health.tick_late_us_p50(), health.tick_late_us_p99(), health.tick_late_us_max()};
  }
}

void BusFigures::addFaultEvent(std::uint64_t step, const std::string& source, const FaultEventSample& event) {
  if (bus::text(event.kind()) != "intruder") return;
  intruders_.push_back({step, source, bus::text(event.topic()), bus::text(event.writer())});
}

nlohmann::ordered_json BusFigures::grants() const {
  if (!granted_) return nlohmann::ordered_json::object();
  return {{"last_step", last_grant_}, {"final_step", final_step_}};
}

void addCompletion(nlohmann::ordered_json& summary, const nlohmann::ordered_json& grants, std::uint64_t record_every) {
  const bool granted = grants.contains("last_step");
  const std::uint64_t last = granted ? grants["last_step"].get<std::uint64_t>() : 0;
  const std::uint64_t final_step = granted ? grants["final_step"].get<std::uint64_t>() : 0;
  const bool completed = granted && final_step - last < record_every;
  summary["completed"] = completed;
  summary["end_reason"] = completed ? std::string("completed")
                          : granted ? "the recording ends at step " + std::to_string(last) + " of " +
                                          std::to_string(final_step)
                                    : std::string("the recording holds no step");
}

void BusFigures::tickLateness(nlohmann::ordered_json& summary) const {
  summary["tick_lateness_us_p50"] = tick_late_[0];
  summary["tick_lateness_us_p99"] = tick_late_[1];
  summary["tick_lateness_us_max"] = tick_late_[2];
}

void BusFigures::lateness(nlohmann::ordered_json& summary) const {
  std::uint64_t stale = 0, overruns = 0, deadlines_missed = 0, dropped = 0, refused = 0;
  nlohmann::ordered_json dropped_by = nlohmann::ordered_json::object();
  for (const auto& [component, last] : health_) {
    stale += last.stale;
    overruns += last.overruns;
    deadlines_missed += last.deadlines_missed;
    dropped += last.dropped;
    refused += last.refused;
    dropped_by[component] = last.dropped;
  }
  summary["stale_inputs"] = stale;
  summary["overruns"] = overruns;
  summary["deadlines_missed"] = deadlines_missed;
  // Received samples that did not decode, as each component's last recorded
  // health counted them (a rogue or broken writer on the bus).
  summary["samples_dropped"] = dropped;
  summary["samples_dropped_by_component"] = dropped_by;
  summary["commands_refused"] = refused;  // mode, fault and parameter commands refused with a reason
}

void BusFigures::trust(nlohmann::ordered_json& summary) const {
  std::uint64_t rejected = 0, clamped = 0, most_intruders = 0;
  nlohmann::ordered_json by_topic = nlohmann::ordered_json::object();
  for (const auto& [component, last] : health_) {
    rejected += last.rejected;
    clamped += last.clamped;
    most_intruders = std::max(most_intruders, last.intruders);
    for (const auto& [topic, n] : last.rejected_by_topic) {
      by_topic[topic] = by_topic.value(topic, std::uint64_t{0}) + n;
    }
  }
  // Each writer once, at its first sighting in step order.
  std::vector<Intruder> in_order = intruders_;
  std::stable_sort(in_order.begin(), in_order.end(), [](const Intruder& a, const Intruder& b) {
    return a.step != b.step ? a.step < b.step : a.source < b.source;
  });
  std::set<std::string> writers;
  nlohmann::ordered_json intruder_writers = nlohmann::ordered_json::array();
  for (const auto& intruder : in_order) {
    if (!writers.insert(intruder.writer).second) continue;
    intruder_writers.push_back({{"step", intruder.step},
                                {"topic", intruder.topic},
                                {"participant", intruder.source},
                                {"writer", intruder.writer}});
  }
  summary["samples_rejected"] = rejected;
  summary["samples_rejected_by_topic"] = by_topic;
  summary["commands_clamped"] = clamped;
  summary["intruders"] = std::max<std::uint64_t>(writers.size(), most_intruders);
  summary["intruder_writers"] = intruder_writers;
}

}  // namespace flatsat::analysis
