// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace flatsat::analysis {

/// The q-quantile of non-empty values sorted ascending, by nearest rank: the
/// smallest value with at least a fraction q of them at or below it (q = 0:
/// the smallest, 0.5: the median, 1: the largest).
inline double nearestRank(const std::vector<double>& sorted, double q) {
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

/// The same of non-empty values in any order. A NaN (a figure that could not
/// be measured) sorts after every number.
inline double quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end(),
            [](double a, double b) { return a < b || (!std::isnan(a) && std::isnan(b)); });
  return nearestRank(values, q);
}

}  // namespace flatsat::analysis
