// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>

namespace flatsat::analysis {

/// Pairs a stream of samples with a reference stream (the truth) by step,
/// as the later of the two arrives, for figures accumulated while a
/// recording is stored. Each stream comes in step order (one producer's
/// samples do), so a pairing happens once per step and the pairings come
/// in step order too: sums over them are the same in every mode and in a
/// read-back. A sample older than the other stream's newest never pairs and
/// is dropped; at most kKept references wait for samples that lag.
template <class Reference, class Sample>
class StepPairs {
 public:
  /// `paired(step, reference, sample)` for the samples waiting on `step`.
  template <class Paired>
  void addReference(std::uint64_t step, const Reference& reference, Paired&& paired) {
    waiting_.erase(waiting_.begin(), waiting_.lower_bound(step));
    const auto [first, end] = waiting_.equal_range(step);
    for (auto it = first; it != end; ++it) paired(step, reference, it->second);
    waiting_.erase(first, end);
    references_.insert_or_assign(step, reference);
    if (references_.size() > kKept) references_.erase(references_.begin());
  }
  /// `paired(step, reference, sample)` at once when the reference of `step` is in.
  template <class Paired>
  void addSample(std::uint64_t step, const Sample& sample, Paired&& paired) {
    references_.erase(references_.begin(), references_.lower_bound(step));
    if (const auto it = references_.find(step); it != references_.end()) {
      paired(step, it->second, sample);
    } else {
      waiting_.emplace(step, sample);
    }
  }

 private:
  static constexpr std::size_t kKept = 1 << 14;
  std::map<std::uint64_t, Reference> references_;
  std::multimap<std::uint64_t, Sample> waiting_;
};

}  // namespace flatsat::analysis
