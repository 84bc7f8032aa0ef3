// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace flatsat::bus {

/// The samples an input holds, by step, in step order: the part of std::map's
/// interface Input uses, over one vector. An input holds one to a few samples
/// and drops the oldest every step; a map gave each sample a heap node (a
/// malloc and a free per sample per input, callgrind), the vector keeps its
/// storage from step to step.
template <class Sample>
class StepSamples {
 public:
  using value_type = std::pair<std::uint64_t, Sample>;
  using iterator = typename std::vector<value_type>::iterator;
  using const_iterator = typename std::vector<value_type>::const_iterator;

  iterator begin() { return items_.begin(); }
  iterator end() { return items_.end(); }
  const_iterator begin() const { return items_.begin(); }
  const_iterator end() const { return items_.end(); }
  bool empty() const { return items_.empty(); }

  /// The first sample stamped at or after `step`.
  const_iterator lower_bound(std::uint64_t step) const {
    return std::lower_bound(items_.begin(), items_.end(), step,
                            [](const value_type& item, std::uint64_t s) { return item.first < s; });
  }
  /// The first sample stamped after `step`.
  const_iterator upper_bound(std::uint64_t step) const {
    return std::upper_bound(items_.begin(), items_.end(), step,
                            [](std::uint64_t s, const value_type& item) { return s < item.first; });
  }
  const_iterator find(std::uint64_t step) const {
    const auto it = lower_bound(step);
    return it != items_.end() && it->first == step ? it : items_.end();
  }
  std::size_t count(std::uint64_t step) const { return find(step) != items_.end() ? 1 : 0; }

  /// Holds `sample` as the one stamped `step`, replacing one held already.
  void insert_or_assign(std::uint64_t step, const Sample& sample) {
    const auto at = items_.begin() + (lower_bound(step) - items_.cbegin());
    if (at != items_.end() && at->first == step) {
      at->second = sample;
    } else {
      items_.emplace(at, step, sample);
    }
  }
  /// Drops the samples in [first, last).
  void erase(const_iterator first, const_iterator last) { items_.erase(first, last); }

 private:
  std::vector<value_type> items_;
};

}  // namespace flatsat::bus
