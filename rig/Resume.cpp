// SPDX-License-Identifier: Apache-2.0
#include "rig/Resume.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "bus/Recording.hpp"
#include "bus/RecordingMeta.hpp"
#include "bus/Topics.hpp"

namespace flatsat::rig {

std::optional<std::uint64_t> prepareResume(const bus::Scenario& scenario, const std::string& recording) {
  if (scenario.pacing != bus::Pacing::kLockstep) {
    throw std::runtime_error(scenario.file + ": mode: paced runs follow the wall clock and cannot be resumed; "
                             "only lockstep runs can");
  }
  if (!std::filesystem::exists(recording)) throw std::runtime_error(recording + ": no recording to resume");
  bus::Recording rec(recording, bus::Recording::Access::kCreate);
  // Operator commands arrived at moments of the wall clock that a resumed rig cannot repeat.
  std::uint64_t commands = 0;
  for (const auto* topic : {&bus::topics::kFaultCmd.name, &bus::topics::kParamCmd.name,
                            &bus::topics::kUnloadingModeCmd.name}) {
    commands += rec.count(std::string(*topic));
  }
  if (commands > 0) {
    throw std::runtime_error(recording + ": holds " + std::to_string(commands) +
                             " operator command(s); a resumed rig could not give them at the same steps");
  }
  // Each producer's samples arrive in step order, so a topic holds every step up to its
  // last sample's, and the steps after it until its producer was next due: the last
  // complete step is the earliest of those.
  const auto schedule = scenario.schedule();
  std::optional<std::uint64_t> complete;
  bool any_topic = false, empty_topic = false;
  bus::forEachTopic([&](const auto& def) {
    if (def.qos != bus::QosKind::kStepped || !schedule.count(std::string(def.producer))) return;
    any_topic = true;
    const auto last = rec.lastStep(std::string(def.name));
    if (!last) {
      empty_topic = true;
      return;
    }
    const std::uint64_t covered = *last + schedule.at(std::string(def.producer)) - 1;
    complete = std::min(complete.value_or(covered), covered);
  });
  if (!any_topic || empty_topic || !complete) return std::nullopt;
  rec.eraseAfter(*complete);
  rec.setMeta(bus::meta::kResumeAfterStep, std::to_string(*complete));
  rec.commit();
  return complete;
}

std::uint64_t resumeMismatches(const std::string& recording) {
  const bus::Recording rec(recording, bus::Recording::Access::kRead);
  const auto text = rec.meta(bus::meta::kResumeMismatches);
  if (text.empty()) throw std::runtime_error(recording + ": the resumed recorder did not report its check");
  return std::stoull(text);
}

}  // namespace flatsat::rig
