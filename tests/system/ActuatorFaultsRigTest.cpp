// SPDX-License-Identifier: Apache-2.0
// Actuator faults from the scenario (spacecraft.faults) in the
// closed loop: the plant applies what each fault's definition says to the
// commands the controllers sent, exactly in its window, and every start and
// end is recorded as a FaultEvent of the dynamics server.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <map>

#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

// Windows in steps of 0.1 s (fault start_s, duration_s below).
constexpr std::uint64_t kCoilOpen = 100;                               // z coil open from 10 s on
constexpr std::uint64_t kDegradedFrom = 200, kDegradedTo = 600;         // wheel 1 at half torque
constexpr std::uint64_t kFailedFrom = 800;                              // wheel 0 dead from 80 s on
constexpr std::uint64_t kStuckFrom = 1000, kStuckTo = 1500;             // wheel 3 frozen
const std::string kFaults =
    "spacecraft.faults=["
    "{kind: coil_open, channel: 2, start_s: 10},"
    "{kind: wheel_degraded, channel: 1, magnitude: 0.5, start_s: 20, duration_s: 40},"
    "{kind: wheel_failed, channel: 0, start_s: 80},"
    "{kind: wheel_stuck, channel: 3, start_s: 100, duration_s: 50}]";

}  // namespace

TEST_CASE("actuator faults from the scenario act on the plant as defined, in their windows",
          "[dynamics_server][system][faults][composed]") {
  const std::string out = test::freshDir("actuator-faults");
  const auto run = test::runCommand(test::kFlatsat + " run " + std::string(FLATSAT_SCENARIO_DIR) +
                                    "/default.yaml --composed -q --no-plots --out " + out +
                                    " --set duration_orbits=null --set duration_s=200 --set '" +
                                    kFaults + "'");
  INFO(run.output);
  REQUIRE(run.exit_code == 0);
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -o " + out +
                           "/export -t truth -t wheel_torque_cmd -t dipole_cmd -t fault_event")
              .exit_code == 0);
  const fs::path exported = fs::path(out) / "export";
  std::map<std::uint64_t, nlohmann::json> truth, wheel_cmd;
  for (auto& row : test::exportedRows(exported, "truth")) truth[row["header"]["step"]] = row;
  for (auto& row : test::exportedRows(exported, "wheel_torque_cmd")) wheel_cmd[row["header"]["step"]] = row;
  REQUIRE(truth.size() == 2001);

  // Truth k + 1 carries the torque the plant applied over [t_k, t_k+1), the
  // controller's command stamped k after the faults.
  std::size_t compared = 0;
  for (const auto& [k, cmd] : wheel_cmd) {
    if (truth.count(k + 1) == 0) continue;
    const auto& applied = truth[k + 1]["wheel_torque_Nm"];
    for (int w = 0; w < 4; ++w) {
      const double commanded = cmd["torque_Nm"][w].get<double>();
      double expected = commanded;
      if (w == 1 && k >= kDegradedFrom && k < kDegradedTo) expected = 0.5 * commanded;
      if (w == 0 && k >= kFailedFrom) expected = 0.0;
      if (w == 3 && k >= kStuckFrom && k < kStuckTo) expected = wheel_cmd[kStuckFrom]["torque_Nm"][3].get<double>();
      INFO("step " << k << " wheel " << w);
      CHECK(applied[w].get<double>() == Approx(expected).margin(1e-15));
    }
    ++compared;
  }
  CHECK(compared == 2000);
  // The unloading controller goes on commanding z; the open coil gives none.
  std::size_t commanded_z = 0;
  for (const auto& row : test::exportedRows(exported, "dipole_cmd")) {
    commanded_z += row["header"]["step"].get<std::uint64_t>() >= kCoilOpen && row["m_body_Am2"][2] != 0.0;
  }
  CHECK(commanded_z > 10);
  for (const auto& [k, row] : truth) {
    if (k > kCoilOpen) CHECK(row["dipole_body_Am2"][2].get<double>() == 0.0);
  }

  std::map<std::string, std::vector<std::pair<std::uint64_t, bool>>> events;  // kind -> (step, active)
  for (const auto& e : test::exportedRows(exported, "fault_event")) {
    if (e["header"]["source"] == "dynamics_server") {
      events[e["kind"].get<std::string>()].push_back({e["header"]["step"], e["active"].get<bool>()});
    }
  }
  using Changes = std::vector<std::pair<std::uint64_t, bool>>;
  CHECK(events["coil_open"] == Changes{{kCoilOpen, true}});
  CHECK(events["wheel_degraded"] == Changes{{kDegradedFrom, true}, {kDegradedTo, false}});
  CHECK(events["wheel_failed"] == Changes{{kFailedFrom, true}});
  CHECK(events["wheel_stuck"] == Changes{{kStuckFrom, true}, {kStuckTo, false}});
  fs::remove_all(out);
}

TEST_CASE("an actuator fault the spacecraft cannot have is refused before the run", "[dynamics_server][system][faults]") {
  const std::string out = test::freshDir("actuator-faults-bad");
  const auto run = test::runCommand(
      test::kFlatsat + " run " + std::string(FLATSAT_SCENARIO_DIR) + "/default.yaml --composed -q --out " +
      out + " --set 'spacecraft.faults=[{kind: thruster_failed, channel: 0}, " +
      "{kind: wheel_failed, channel: 4}, {kind: wheel_degraded, channel: 0, magnitude: 2}]'");
  INFO(run.output);
  CHECK(run.exit_code == 2);
  CHECK(run.output.find("thruster_failed: the spacecraft has no such actuator") != std::string::npos);
  CHECK(run.output.find("channel: must be -1 (all) or 0..3") != std::string::npos);
  CHECK(run.output.find("magnitude: wheel_degraded takes the torque fraction left, in [0, 1]") !=
        std::string::npos);
  fs::remove_all(out);
}
