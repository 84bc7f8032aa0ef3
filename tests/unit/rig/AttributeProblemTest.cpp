// SPDX-License-Identifier: Apache-2.0
// A problem of a resolved scenario, told where the user wrote the key.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "rig/RunDirectory.hpp"

using flatsat::rig::attributeProblem;

TEST_CASE("a resolved scenario's problem is told at the --set or the user's own line", "[campaign]") {
  const auto file = std::filesystem::temp_directory_path() / ("flatsat-attr-" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(file) << "name: x\ncomponents:\n  gyro:\n    noise_rad_s: -1\n";
  const std::string resolved = "/tmp/run/scenario.yaml";
  const std::vector<std::string> sets{"components.estimator.gain=3", "seed=4"};
  // From a --set (the key itself, or a key below it).
  CHECK(attributeProblem(resolved + ":40:7: components.estimator.gain: must be > 0", resolved, file.string(), sets) ==
        "--set components.estimator.gain=3: components.estimator.gain: must be > 0");
  // From the user's file: its own line and column (1-based), not the resolved copy's.
  CHECK(attributeProblem(resolved + ":75:5: components.gyro.noise_rad_s: must be >= 0", resolved, file.string(),
                         sets) == file.string() + ":4:18: components.gyro.noise_rad_s: must be >= 0");
  // Neither (a key from a base file): as it was; a problem of another file: as it was.
  const std::string from_base = resolved + ":9:3: orbit.altitude_m: out of range";
  CHECK(attributeProblem(from_base, resolved, file.string(), sets) == from_base);
  CHECK(attributeProblem("other.yaml:1:1: x: y", resolved, file.string(), sets) == "other.yaml:1:1: x: y");
  std::filesystem::remove(file);
}
