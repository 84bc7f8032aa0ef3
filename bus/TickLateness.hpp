// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>

namespace flatsat::bus {

/// How late a paced time master granted its steps against the period grid,
/// in 1 µs bins up to kBins µs (later ones count in the last bin; the
/// largest is kept exactly): fixed memory however long the run.
class TickLateness {
 public:
  static constexpr std::size_t kBins = 50'000;

  void add(std::chrono::nanoseconds late) {
    const double us = std::max(0.0, static_cast<double>(late.count()) * 1e-3);
    ++bins_[std::min<std::size_t>(kBins - 1, static_cast<std::size_t>(us))];
    ++count_;
    max_us_ = std::max(max_us_, us);
  }
  /// [µs] nearest-rank quantile q in (0, 1]: the upper edge of its bin; 0 when empty.
  double quantileUs(double q) const {
    if (count_ == 0) return 0.0;
    const auto rank = static_cast<std::uint64_t>(std::max(1.0, std::ceil(q * static_cast<double>(count_))));
    std::uint64_t seen = 0;
    for (std::size_t i = 0; i < kBins; ++i) {
      seen += bins_[i];
      if (seen >= rank) return i + 1 == kBins ? max_us_ : std::min(max_us_, static_cast<double>(i + 1));
    }
    return max_us_;
  }
  double maxUs() const { return max_us_; }

 private:
  std::array<std::uint32_t, kBins> bins_{};
  std::uint64_t count_ = 0;
  double max_us_ = 0.0;
};

}  // namespace flatsat::bus
