// SPDX-License-Identifier: Apache-2.0
#include "bus/BusFaults.hpp"

#include <algorithm>
#include <cmath>

namespace flatsat::bus {

namespace {

constexpr double kMaxDelay_s = 10.0;

/// SplitMix64's finaliser (Steele, Lea & Flood, "Fast splittable
/// pseudorandom number generators", OOPSLA 2014): a full-avalanche mix, so
/// neighbouring steps give independent picks.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::uint64_t fnv1a(std::string_view text) {
  std::uint64_t hash = 14695981039346656037ULL;
  for (char c : text) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ULL;
  }
  return hash;
}

}  // namespace

const char* toString(BusFaultKind kind) {
  switch (kind) {
    case BusFaultKind::kDrop: return "drop";
    case BusFaultKind::kDelay: return "delay";
    case BusFaultKind::kDuplicate: return "duplicate";
  }
  return "?";
}

bool parseBusFaultKind(std::string_view text, BusFaultKind& kind) {
  for (auto k : {BusFaultKind::kDrop, BusFaultKind::kDelay, BusFaultKind::kDuplicate}) {
    if (text == toString(k)) {
      kind = k;
      return true;
    }
  }
  return false;
}

std::vector<std::string> BusFault::validate() const {
  std::vector<std::string> problems;
  if (kind == BusFaultKind::kDelay) {
    if (!(magnitude > 0.0 && magnitude <= kMaxDelay_s)) problems.push_back("magnitude: a delay must be in (0, 10] s");
  } else if (!(magnitude > 0.0 && magnitude <= 1.0)) {
    problems.push_back(std::string("magnitude: the fraction of samples to ") + toString(kind) +
                       " must be in (0, 1]");
  }
  if (start_ns < 0) problems.push_back("start_s: must be >= 0");
  if (duration_ns < 0) problems.push_back("duration_s: must be >= 0 (0: for the rest of the run)");
  return problems;
}

BusFaultPlan::BusFaultPlan(std::string topic, std::uint64_t seed, std::int64_t period_ns)
    : key_(mix(seed ^ fnv1a(topic))), period_ns_(period_ns) {}

void BusFaultPlan::add(const BusFault& fault) {
  std::lock_guard lock(mutex_);
  faults_.push_back(fault);
  empty_.store(false, std::memory_order_release);
}

std::vector<BusFault> BusFaultPlan::faults() const {
  std::lock_guard lock(mutex_);
  return faults_;
}

double BusFaultPlan::pick(std::uint64_t step, std::size_t fault_index) const {
  const std::uint64_t bits = mix(key_ ^ mix(step * 0x100000001B3ULL + fault_index));
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

bool BusFaultPlan::hits(BusFaultKind kind, std::uint64_t step) const {
  for (std::size_t i = 0; i < faults_.size(); ++i) {
    const BusFault& f = faults_[i];
    if (f.kind == kind && f.actsAt(timeOf(step)) && pick(step, i) < f.magnitude) return true;
  }
  return false;
}

bool BusFaultPlan::dropped(std::uint64_t step) const {
  if (empty()) return false;
  std::lock_guard lock(mutex_);
  return hits(BusFaultKind::kDrop, step);
}

bool BusFaultPlan::duplicated(std::uint64_t step) const {
  if (empty()) return false;
  std::lock_guard lock(mutex_);
  return hits(BusFaultKind::kDuplicate, step);
}

std::uint64_t BusFaultPlan::delaySteps(std::uint64_t step) const {
  if (empty()) return 0;
  std::lock_guard lock(mutex_);
  return lateBy(step);
}

std::uint64_t BusFaultPlan::lateBy(std::uint64_t step) const {
  std::uint64_t steps = 0;
  for (const auto& f : faults_) {
    if (f.kind != BusFaultKind::kDelay || !f.actsAt(timeOf(step))) continue;
    // A delay shorter than a step still misses its step: at least one.
    const auto late = std::max<std::int64_t>(1, std::llround(f.magnitude * 1e9 / static_cast<double>(period_ns_)));
    steps = std::max(steps, static_cast<std::uint64_t>(late));
  }
  return steps;
}

bool BusFaultPlan::actsAt(std::uint64_t step) const {
  if (empty()) return false;
  std::lock_guard lock(mutex_);
  return std::any_of(faults_.begin(), faults_.end(), [&](const BusFault& f) { return f.actsAt(timeOf(step)); });
}

std::optional<std::uint64_t> BusFaultPlan::faultedStamp(std::uint64_t j, std::uint32_t divider) const {
  std::uint64_t s = j - j % divider;
  const auto before = [&](std::uint64_t step) -> std::optional<std::uint64_t> {  // the grid point before
    if (step < divider) return std::nullopt;
    const std::uint64_t p = step - 1;
    return p - p % divider;
  };
  std::lock_guard lock(mutex_);
  for (;;) {
    // A drop of every sample over a window: jump to the grid point before it
    // (a long outage would otherwise be walked back sample by sample).
    std::optional<std::uint64_t> outage_start;
    for (const auto& f : faults_) {
      if (f.kind == BusFaultKind::kDrop && f.magnitude >= 1.0 && f.actsAt(timeOf(s))) {
        const auto first = static_cast<std::uint64_t>((f.start_ns + period_ns_ - 1) / period_ns_);
        outage_start = std::min(outage_start.value_or(first), first);
      }
    }
    std::optional<std::uint64_t> next;
    if (outage_start) {
      next = before(std::min(s, *outage_start));
    } else if (!hits(BusFaultKind::kDrop, s) && s + lateBy(s) <= j) {
      return s;
    } else {
      next = before(s);
    }
    if (!next) return std::nullopt;
    s = *next;
  }
}

BusFaultTable::BusFaultTable(std::uint64_t seed, std::int64_t period_ns, const std::vector<BusFault>& faults)
    : seed_(seed), period_ns_(period_ns) {
  for (const auto& fault : faults) add(fault);
}

BusFaultPlan& BusFaultTable::plan(const std::string& topic) {
  std::lock_guard lock(mutex_);
  auto& slot = plans_[topic];
  if (!slot) slot = std::make_unique<BusFaultPlan>(topic, seed_, period_ns_);
  return *slot;
}

std::map<std::string, const BusFaultPlan*> BusFaultTable::faulted() const {
  std::lock_guard lock(mutex_);
  std::map<std::string, const BusFaultPlan*> out;
  for (const auto& [topic, plan] : plans_) {
    if (!plan->empty()) out.emplace(topic, plan.get());
  }
  return out;
}

}  // namespace flatsat::bus
