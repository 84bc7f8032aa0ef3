// SPDX-License-Identifier: Apache-2.0
#pragma once
// "did you mean": the known name nearest a misspelled one, by optimal string
// alignment distance (Levenshtein with adjacent swaps, as Git and CLI tools
// suggest), when it is close enough to be the likely intent.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace flatsat::bus {

inline std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

/// The candidate nearest `word` if at most a third of its letters (at least
/// one, at most three) must change; nullopt when none is that near.
inline std::optional<std::string> nearestName(const std::string& word, const std::vector<std::string>& candidates) {
  const std::size_t allowed = std::clamp<std::size_t>(word.size() / 3, 1, 3);
  std::optional<std::string> best;
  std::size_t best_distance = allowed + 1;
  for (const auto& candidate : candidates) {
    const std::size_t distance = editDistance(word, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

/// " (did you mean 'x'?)" or "".
inline std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates) {
  const auto near = nearestName(word, candidates);
  return near ? " (did you mean '" + *near + "'?)" : "";
}

}  // namespace flatsat::bus
