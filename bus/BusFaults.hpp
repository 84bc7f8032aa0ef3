// SPDX-License-Identifier: Apache-2.0
#pragma once
// Faults of the bus itself (architecture, "Faults"): the samples of one
// stepped topic dropped, delayed or duplicated on their way to its readers.
//
// A drop or a delay is applied by every consuming reader (bus::Input) with
// the same answers in every process: which samples a fault hits is a hash of
// the scenario seed, the topic and the sample's step, never a draw from a
// shared generator, so a lockstep run stays deterministic and a composed run
// sees what a multi-process one sees. A reader at step k goes on with the
// newest sample that has reached it: the one due, or an older one when the
// due one was dropped or is still on its way. A duplicate is a real second
// write by the producer, which readers must (and do) pass on once.
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace flatsat::bus {

enum class BusFaultKind { kDrop, kDelay, kDuplicate };

const char* toString(BusFaultKind kind);
/// false: not a bus fault kind.
bool parseBusFaultKind(std::string_view text, BusFaultKind& kind);
inline constexpr const char* kBusFaultKinds = "drop, delay, duplicate";
/// The FaultCmd target that addresses the bus.
inline constexpr const char* kBusFaultTarget = "bus";

struct BusFault {
  BusFaultKind kind = BusFaultKind::kDrop;
  std::string topic;             ///< a stepped topic of the registry (bus/Topics.hpp)
  /// drop, duplicate: [-] fraction of the samples hit, (0, 1] (1: every one);
  /// delay: [s] how late each sample arrives, (0, 10]
  double magnitude = 1.0;
  std::int64_t start_ns = 0;     ///< [ns] simulated time it begins, >= 0
  std::int64_t duration_ns = 0;  ///< [ns] > 0, or 0 for the rest of the run

  /// Every problem as "field: reason" (empty: valid). The topic is checked
  /// against the registry by the caller (it knows which topics exist).
  std::vector<std::string> validate() const;
  /// Whether it acts on a sample stamped at simulated time t.
  bool actsAt(std::int64_t t_ns) const {
    return t_ns >= start_ns && (duration_ns == 0 || t_ns - start_ns < duration_ns);
  }
};

/// The bus faults of one topic. Thread-safe: faults commanded at run time
/// arrive on a middleware thread while readers ask.
class BusFaultPlan {
 public:
  BusFaultPlan(std::string topic, std::uint64_t seed, std::int64_t period_ns);

  void add(const BusFault& fault);
  /// No fault at all (the common case): one atomic load.
  bool empty() const { return empty_.load(std::memory_order_acquire); }
  std::vector<BusFault> faults() const;

  /// Whether the sample stamped `step` never reaches a consuming reader.
  bool dropped(std::uint64_t step) const;
  /// [steps] how late the sample stamped `step` reaches them (0: in its step).
  std::uint64_t delaySteps(std::uint64_t step) const;
  /// Whether its producer writes the sample stamped `step` twice.
  bool duplicated(std::uint64_t step) const;
  /// Whether any fault acts on a sample stamped `step`.
  bool actsAt(std::uint64_t step) const;

  /// The stamp of the sample a consuming reader holds at producer step j of
  /// a producer due every `divider` steps: the newest stamp s <= j on the
  /// producer's grid that was not dropped and has arrived (s + delay <= j);
  /// nothing when no sample has.
  std::optional<std::uint64_t> visibleStamp(std::uint64_t j, std::uint32_t divider) const {
    if (empty()) return j - j % divider;  // inline: every input asks this for every sample
    return faultedStamp(j, divider);
  }

 private:
  std::optional<std::uint64_t> faultedStamp(std::uint64_t j, std::uint32_t divider) const;
  /// The fault's pick for this step: uniform in [0, 1), the same everywhere.
  double pick(std::uint64_t step, std::size_t fault_index) const;
  bool hits(BusFaultKind kind, std::uint64_t step) const;  // caller holds mutex_
  std::uint64_t lateBy(std::uint64_t step) const;           // delaySteps(); caller holds mutex_
  std::int64_t timeOf(std::uint64_t step) const { return static_cast<std::int64_t>(step) * period_ns_; }

  std::uint64_t key_;       // seed mixed with the topic
  std::int64_t period_ns_;  // [ns] base step period
  mutable std::mutex mutex_;
  std::vector<BusFault> faults_;
  std::atomic<bool> empty_{true};
};

/// Every topic's plan for the readers and writers of one node.
class BusFaultTable {
 public:
  BusFaultTable(std::uint64_t seed, std::int64_t period_ns, const std::vector<BusFault>& faults);
  /// The topic's plan (created without faults on first use); the reference stays valid.
  BusFaultPlan& plan(const std::string& topic);
  void add(const BusFault& fault) { plan(fault.topic).add(fault); }
  /// Every plan with at least one fault, by topic.
  std::map<std::string, const BusFaultPlan*> faulted() const;

 private:
  std::uint64_t seed_;
  std::int64_t period_ns_;
  mutable std::mutex mutex_;
  std::map<std::string, std::unique_ptr<BusFaultPlan>> plans_;
};

}  // namespace flatsat::bus
