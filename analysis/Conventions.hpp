// SPDX-License-Identifier: Apache-2.0
#pragma once
// What the flatsat commands share: how they exit on bad input, and degrees.
#include <numbers>

namespace flatsat::analysis {

/// Exit code of a command for input it refuses (a scenario, a file, an
/// option), as a component's process exits for a bad configuration.
inline constexpr int kExitBadInput = 2;
/// [deg/rad] and [rad/deg]
inline constexpr double kRadToDeg = 180.0 / std::numbers::pi;
inline constexpr double kDeg = std::numbers::pi / 180.0;

}  // namespace flatsat::analysis
