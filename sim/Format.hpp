// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdio>
#include <string>

namespace flatsat::sim {

/// Shortest readable form of a number for error messages ("6378137", "1e-09", "nan").
inline std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.10g", value);
  return text;
}

}  // namespace flatsat::sim
