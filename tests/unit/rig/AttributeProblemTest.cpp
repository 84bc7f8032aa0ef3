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
  // Neither: the user's file, without the resolved copy's line; a problem of another file: as it was.
  CHECK(attributeProblem(resolved + ":9:3: orbit.altitude_m: out of range", resolved, file.string(), sets) ==
        file.string() + ": orbit.altitude_m: out of range");
  CHECK(attributeProblem("other.yaml:1:1: x: y", resolved, file.string(), sets) == "other.yaml:1:1: x: y");
  // A problem without a place (a bound found from several keys) still finds its --set.
  CHECK(attributeProblem(resolved + ": seed: too large", resolved, file.string(), sets) ==
        "--set seed=4: seed: too large");
  std::filesystem::remove(file);
}

TEST_CASE("a resolved scenario's problem of a key its base writes is told at the base's line", "[campaign]") {
  const auto dir = std::filesystem::temp_directory_path() / ("flatsat-attr-base-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "base.yaml") << "name: b\norbit:\n  altitude_m: 9 km\n";
  std::ofstream(dir / "mine.yaml") << "base: base.yaml\nname: mine\norbit:\n  eccentricity: 0.5\n";
  const std::string resolved = "/tmp/run/scenario.yaml";
  const std::string mine = (dir / "mine.yaml").string(), base = (dir / "base.yaml").string();
  CHECK(attributeProblem(resolved + ":3:3: orbit.altitude_m: too low", resolved, mine, {}) ==
        base + ":3:15: orbit.altitude_m: too low");
  CHECK(attributeProblem(resolved + ":4:3: orbit.eccentricity: too high", resolved, mine, {}) ==
        mine + ":4:17: orbit.eccentricity: too high");
  std::filesystem::remove_all(dir);
}
