// SPDX-License-Identifier: Apache-2.0
#pragma once
// The summary's verdicts on the run itself (architecture, "Trust on the
// bus"): whether it ran to its last step, how late its components were and
// what its consumers refused, accumulated sample by sample
// (analysis/RunFigures.hpp).
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bus/Topics.hpp"

namespace flatsat::analysis {

using GrantSample = std::remove_cvref_t<decltype(bus::topics::kStepGrant)>::Type;
using HealthSample = std::remove_cvref_t<decltype(bus::topics::kHealth)>::Type;
using FaultEventSample = std::remove_cvref_t<decltype(bus::topics::kFaultEvent)>::Type;

class BusFigures {
 public:
  void addGrant(std::uint64_t step, const GrantSample& grant);
  /// A component's health; the one of its highest step (then the later) counts.
  void addHealth(std::uint64_t step, const std::string& source, const HealthSample& health);
  void addFaultEvent(std::uint64_t step, const std::string& source, const FaultEventSample& event);
  /// {"last_step", "final_step"} of the last recorded grant; {} without one.
  nlohmann::ordered_json grants() const;
  /// How late the paced time master granted the steps, as it measured them
  /// (bus/TickLateness.hpp): tick_lateness_us_p50, _p99, _max.
  void tickLateness(nlohmann::ordered_json& summary) const;
  /// stale_inputs, overruns, deadlines_missed, samples_dropped (and by
  /// component), commands_refused: the components' last counts, summed.
  void lateness(nlohmann::ordered_json& summary) const;
  /// `samples_rejected` (and by topic, over every component),
  /// `commands_clamped`, and `intruders`: the writers seen on a topic that the
  /// scenario does not declare as its producer (the recorder's fault events
  /// of kind "intruder", with each writer's GUID and participant in
  /// `intruder_writers`; at least as many as any one component counted).
  void trust(nlohmann::ordered_json& summary) const;

 private:
  struct LastHealth {
    std::uint64_t step = 0;
    std::uint64_t stale = 0, overruns = 0, deadlines_missed = 0, dropped = 0, refused = 0;
    std::uint64_t rejected = 0, clamped = 0, intruders = 0;
    std::map<std::string, std::uint64_t> rejected_by_topic;
  };
  struct Intruder {
    std::uint64_t step;
    std::string source, topic, writer;
  };
  bool granted_ = false;
  std::uint64_t last_grant_ = 0, final_step_ = 0;
  std::map<std::string, LastHealth> health_;  // by component
  std::array<double, 3> tick_late_{};         // [µs] the paced time master's last p50, p99, max
  std::uint64_t tick_late_step_ = 0;
  std::vector<Intruder> intruders_;
};

/// `completed` (the recording holds the grant of the run's final step, as the
/// time master stamped it; a decimated one, `record_every` > 1, its last
/// recorded multiple) and `end_reason` ("completed", or where the recording
/// ends), from BusFigures::grants().
void addCompletion(nlohmann::ordered_json& summary, const nlohmann::ordered_json& grants, std::uint64_t record_every);

}  // namespace flatsat::analysis
