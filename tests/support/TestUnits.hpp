// SPDX-License-Identifier: Apache-2.0
#pragma once
// Constants and helpers that test files share, defined once: the test
// executables compile their files several to a translation unit
// (cmake/BuildSpeed.cmake), where a file's own second definition of kDeg
// would clash with its neighbour's.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/Constants.hpp"

// sim's own, so that a file using namespace flatsat::sim sees one kPi, not two.
using flatsat::sim::kPi;
inline constexpr double kDeg = kPi / 180.0;                  ///< [rad] one degree
inline constexpr double kMu = flatsat::sim::kMuEarth_m3_s2;  ///< [m³/s²]
inline constexpr std::int64_t kSecond = 1'000'000'000;       ///< [ns] one second
/// The rigs' usual step, 10 Hz, as the sensor and filter tests run it.
inline constexpr std::int64_t kStep10Hz_ns = 100'000'000;     ///< [ns]
inline constexpr double kStep10Hz_s = 0.1;                    ///< [s]

/// [ns] the nearest to t_s seconds.
inline std::int64_t ns(double t_s) { return std::llround(t_s * 1e9); }

/// Whether one of the problems a validate() lists starts with prefix ("key: reason").
inline bool anyStartsWith(const std::vector<std::string>& problems, const std::string& prefix) {
  for (const std::string& p : problems) {
    if (p.rfind(prefix, 0) == 0) return true;
  }
  return false;
}
