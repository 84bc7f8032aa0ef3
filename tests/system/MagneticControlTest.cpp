// SPDX-License-Identifier: Apache-2.0
// B-dot detumbling and the seed S4 spin capture on the whole rig, judged on
// the recorded truth against their limits (detumble: below 0.2 deg/s within
// 3 orbits; spin: within 5 deg and 5 % within 5 orbits).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"

using namespace flatsat;

namespace {

using test::kFlatsat;

/// Composed (ComposedTest: the same recording as the multi-process rig): orbits in seconds.
nlohmann::json runComposed(const std::string& file, const std::string& tag, const std::string& extra) {
  return test::runScenario(std::string(FLATSAT_SCENARIO_DIR) + "/" + file, test::freshDir(tag), "--composed " + extra)
      .summary;
}

/// The numeric rows of `flatsat study NAME --cases 50 [--scenario FILE]`'s table, each
/// with `columns` values; "never" and "inf" (not captured) read as infinity.
std::vector<std::vector<double>> studyRows(const std::string& name, std::size_t columns,
                                           const std::string& scenario = "") {
  const auto command = test::runCommand(kFlatsat + " study " + name + " --cases 50" +
                                        (scenario.empty() ? "" : " --scenario " + std::string(FLATSAT_SCENARIO_DIR) +
                                                                     "/" + scenario));
  INFO(command.output);
  REQUIRE(command.exit_code == 0);
  std::vector<std::vector<double>> rows;
  std::istringstream lines(command.output);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream cells(line);
    std::vector<double> row;
    std::string bar, cell;
    while (cells >> bar && bar == "|" && cells >> cell) {
      if (cell == "never" || cell == "inf") {
        row.push_back(std::numeric_limits<double>::infinity());
        continue;
      }
      char* end = nullptr;
      const double value = std::strtod(cell.c_str(), &end);
      if (end == cell.c_str() || *end != '\0') break;
      row.push_back(value);
    }
    if (row.size() == columns) rows.push_back(row);
  }
  return rows;
}

/// The median of one column.
double median(const std::vector<std::vector<double>>& rows, std::size_t column) {
  std::vector<double> values;
  for (const auto& row : rows) values.push_back(row[column]);
  std::sort(values.begin(), values.end());
  return values.empty() ? NAN : 0.5 * (values[(values.size() - 1) / 2] + values[values.size() / 2]);
}

}  // namespace

TEST_CASE("B-dot detumbles the rig from 10 deg/s below 0.2 deg/s within 3 orbits", "[unloading_controller][system][bdot]") {
  // Seed 2 of `flatsat study detumble`, run over DDS with every component its own process.
  const auto s = runComposed("detumble.yaml", "detumble", "--seed 2");
  INFO(s.dump(2));
  REQUIRE_FALSE(s["time_to_detumble_s"].is_null());
  CHECK(s["rate_deg_s_final"].get<double>() < 0.2);
  CHECK(s["sim_seconds"].get<double>() <= 3.0 * 5740.0);  // 3 orbits at 550 km (95.6 min)
  CHECK(s["coil_duty"].get<double>() > 0.0);
  CHECK(s["coil_duty"].get<double>() <= 1.0);
}

TEST_CASE("B-dot: all 50 seeded tumbles of 10 deg/s below 0.2 deg/s within 3 orbits", "[unloading_controller][system][bdot]") {
  // `flatsat study detumble` runs detumble.yaml's plant, magnetometer and controller without
  // DDS; a case counts when its rate is below 0.2 deg/s within 3 orbits and stays there.
  const auto rows = studyRows("detumble", 5);
  for (const auto& row : rows) {
    INFO("seed " << row[0]);  // | seed | detumbled [s] | [orbits] | final rate [deg/s] | coil duty |
    CHECK(row[2] <= 3.0);
    CHECK(row[3] < 0.2);
    CHECK(row[4] > 0.0);
  }
  CHECK(rows.size() == 50);
}

TEST_CASE("S4 spin capture holds body z within 5 deg of the orbit normal at 2 deg/s within 5 orbits", "[unloading_controller][system][bdot]") {
  const auto s = runComposed("s4_spin.yaml", "s4spin", "--seed 3");
  INFO(s.dump(2));
  REQUIRE_FALSE(s["time_to_capture_s"].is_null());
  CHECK(s["time_to_capture_s"].get<double>() <= 5.0 * 5740.0);  // captured and held to the end (6 orbits)
  CHECK(s["spin_axis_error_deg"].get<double>() < 5.0);
  CHECK(s["spin_rate_error_pct"].get<double>() < 5.0);
  CHECK(s["coil_duty"].get<double>() > 0.0);
}

TEST_CASE("S4 spin capture: the corrected law captures all 50 seeded tumbles, the seed's as written none",
          "[unloading_controller][system][bdot]") {
  // `flatsat study spin` runs the scenario's plant, magnetometer and controller
  // without DDS; each row is judged on the truth over the whole run.
  // | seed | handover | capture | [orbits] | axis | rate | axis, orbit 5 | rate, orbit 5 | duty |
  // Measured (docs/magnetic_control.md, "The seed's law as written"), pinned at 1.5×.
  const auto corrected = studyRows("spin", 9);
  REQUIRE(corrected.size() == 50);
  for (const auto& row : corrected) {
    INFO("corrected, seed " << row[0]);
    CHECK(row[3] <= 1.5 * 1.79);  // orbits from release to capture
    CHECK(row[6] < 5.0);          // worst over orbit 5
    CHECK(row[7] < 5.0);
    CHECK(row[4] < 1.5 * 2.67);   // axis [deg] at the end
    CHECK(row[5] < 1.5 * 0.45);   // rate [%] at the end
  }
  CHECK(median(corrected, 4) < 1.5 * 0.87);
  CHECK(median(corrected, 5) < 1.5 * 0.205);

  // s4_spin_seed.yaml: the seed's P = Ḃ − B_k × ω0 a, nothing added, on the same plant
  // and tumbles. It spins the body at about its rest rate 3ω0, but at 0.19 deg/s the
  // bang-bang torque and gravity gradient leave the axis anywhere: no seed captured.
  const auto seed = studyRows("spin", 9, "s4_spin_seed.yaml");
  REQUIRE(seed.size() == 50);
  for (const auto& row : seed) CHECK(std::isinf(row[2]));
  CHECK(median(seed, 4) > 44.5 / 1.5);
  CHECK(median(seed, 4) < 44.5 * 1.5);
  CHECK(median(seed, 5) > 20.7 / 1.5);
  CHECK(median(seed, 5) < 20.7 * 1.5);
  CHECK(median(seed, 8) == Approx(median(corrected, 8)).epsilon(0.05));  // coils on ~97 % either way
}

TEST_CASE("S4 as written on the rig (s4_spin_seed.yaml): summary keys say it never captures",
          "[unloading_controller][system][bdot]") {
  const auto s = runComposed("s4_spin_seed.yaml", "s4seed", "--seed 3");
  INFO(s.dump(2));
  CHECK(s["time_to_capture_s"].is_null());
  // Spun up, not aligned (the study's row for seed 3: axis 62.9 deg, rate 7.8 % off 3ω0).
  CHECK(s["spin_axis_error_deg"].get<double>() > 5.0);
  CHECK(s["coil_duty"].get<double>() > 0.9);
}
