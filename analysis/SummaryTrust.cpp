// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryTrust.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "bus/RecordingMeta.hpp"
#include "bus/Serialization.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"

namespace flatsat::analysis {

void addCompletion(nlohmann::ordered_json& summary, const bus::Recording& recording) {
  const std::string grants(bus::topics::kStepGrant.name);
  const auto last = recording.lastStep(grants);
  std::uint64_t final_step = 0;
  if (last) {
    using GrantDef = std::remove_cvref_t<decltype(bus::topics::kStepGrant)>;
    recording.forEachAt(grants, *last, [&](const std::string&, const std::vector<std::uint8_t>& bytes) {
      final_step = bus::deserialize<GrantDef>(bytes).final_step();
    });
  }
  const std::string every = recording.meta(bus::meta::kRecordEverySteps);
  const std::uint64_t record_every = every.empty() ? 1 : std::stoull(every);
  const bool completed = last && final_step - *last < record_every;
  summary["completed"] = completed;
  summary["end_reason"] = completed ? std::string("completed")
                          : last    ? "the recording ends at step " + std::to_string(*last) + " of " +
                                       std::to_string(final_step)
                                    : std::string("the recording holds no step");
}

void addTrustMetrics(nlohmann::ordered_json& summary, const bus::Recording& recording) {
  struct Counts {
    std::uint64_t rejected = 0, clamped = 0, intruders = 0;
    std::map<std::string, std::uint64_t> by_topic;
  };
  std::map<std::string, Counts> last;  // each component's last health
  using HealthDef = std::remove_cvref_t<decltype(bus::topics::kHealth)>;
  recording.forEach(std::string(bus::topics::kHealth.name),
                    [&](std::uint64_t, const std::string& source, const std::vector<std::uint8_t>& bytes) {
                      const auto health = bus::deserialize<HealthDef>(bytes);
                      Counts counts{health.samples_rejected(), health.commands_clamped(), health.intruders(), {}};
                      for (const auto& slot : health.rejected_by_topic()) {
                        if (slot.count() > 0) counts.by_topic[bus::text(slot.topic())] = slot.count();
                      }
                      last[source] = std::move(counts);
                    });
  std::uint64_t rejected = 0, clamped = 0, most_intruders = 0;
  nlohmann::ordered_json by_topic = nlohmann::ordered_json::object();
  for (const auto& [component, counts] : last) {
    rejected += counts.rejected;
    clamped += counts.clamped;
    most_intruders = std::max(most_intruders, counts.intruders);
    for (const auto& [topic, n] : counts.by_topic) {
      by_topic[topic] = by_topic.value(topic, std::uint64_t{0}) + n;
    }
  }
  std::set<std::string> writers;
  nlohmann::ordered_json intruder_writers = nlohmann::ordered_json::array();
  using EventDef = std::remove_cvref_t<decltype(bus::topics::kFaultEvent)>;
  recording.forEach(std::string(bus::topics::kFaultEvent.name),
                    [&](std::uint64_t step, const std::string& source, const std::vector<std::uint8_t>& bytes) {
                      const auto event = bus::deserialize<EventDef>(bytes);
                      if (bus::text(event.kind()) != "intruder" || !writers.insert(bus::text(event.writer())).second) {
                        return;
                      }
                      intruder_writers.push_back({{"step", step},
                                                  {"topic", bus::text(event.topic())},
                                                  {"participant", source},
                                                  {"writer", bus::text(event.writer())}});
                    });
  summary["samples_rejected"] = rejected;
  summary["samples_rejected_by_topic"] = by_topic;
  summary["commands_clamped"] = clamped;
  summary["intruders"] = std::max<std::uint64_t>(writers.size(), most_intruders);
  summary["intruder_writers"] = intruder_writers;
}

}  // namespace flatsat::analysis
