// SPDX-License-Identifier: Apache-2.0
// A component that dies is noticed through the liveliness of its health
// writer (bus::kHealthLease), not through a step timeout: the component runs
// as `role: external` (started here, as another host would), and is
// SIGKILLed mid-run. In lockstep the rig stops within the lease and names
// it; paced, the rig goes on, records the loss and `flatsat health` shows the
// component dead.
#include <catch2/catch.hpp>

#include <signal.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/Background.hpp"
#include "tests/support/Rig.hpp"
#include "tests/support/ScopedEnv.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

using test::kDefault;

/// The rig of `mode` with wheel_tach external, and wheel_tach started by hand once the rig wrote its scenario.
struct RigWithExternalTach {
  RigWithExternalTach(const std::string& out, const std::string& mode, double duration_s)
      : rig(test::kFlatsat + " run " + kDefault + " -q --no-plots --external wheel_tach --out " + out +
                " --set mode=" + mode + " --set duration_orbits=null --set duration_s=" + std::to_string(duration_s),
            out + ".log") {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!fs::exists(fs::path(out) / "scenario.yaml") && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    tach = std::make_unique<test::Background>(std::string(FLATSAT_BIN_DIR) + "/flatsat-wheel_tach --scenario " + out +
                                                  "/scenario.yaml --name wheel_tach --out " + out,
                                              out + "-tach.log");
  }
  test::Background rig;
  std::unique_ptr<test::Background> tach;
};

}  // namespace

TEST_CASE("lockstep: a component killed mid-run stops the rig within the health lease, named",
          "[system][liveliness]") {
  test::exportTestDomain();
  const std::string out = test::freshDir("liveliness-lockstep");
  RigWithExternalTach rigs(out, "lockstep", 100000);  // far longer than the test: only the kill ends it
  REQUIRE(test::waitForText(fs::path(out) / "logs" / "dynamics_server.log", "every component ready", 60, rigs.rig));
  std::this_thread::sleep_for(std::chrono::seconds(2));
  const auto killed = std::chrono::steady_clock::now();
  rigs.tach->signal(SIGKILL);
  const int code = rigs.rig.wait(40);
  const double noticed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - killed).count();
  const std::string log = test::readFile(out + ".log");
  INFO(log);
  CHECK(code != 0);
  CHECK(code != -1);
  // The lease is 3 s; the step timeout it replaces is 60 s.
  CHECK(noticed_s < 10.0);
  // Named by whichever sees it first: the launcher or the time master.
  CHECK((log.find("external component 'wheel_tach' lost its liveliness") != std::string::npos ||
         log.find("wheel_tach (no liveliness for 3000 ms: its process is gone)") != std::string::npos));
  fs::remove_all(out);
  fs::remove(out + ".log");
  fs::remove(out + "-tach.log");
  fs::remove(out + "-health.log");
}

TEST_CASE("paced: a component killed mid-run is shown dead within the lease and recorded, the rig goes on",
          "[system][liveliness][paced]") {
  test::exportTestDomain();
  const std::string out = test::freshDir("liveliness-paced");
  RigWithExternalTach rigs(out, "paced", 20);
  REQUIRE(test::waitForText(fs::path(out) / "logs" / "dynamics_server.log", "every component ready", 60, rigs.rig));
  // The health table as an operator watches it, from before the kill (a tool
  // started after it could not get the dead writer's last sample).
  const std::string watch_log = out + "-health.log";
  test::Background watch(test::kFlatsat + " health --json", watch_log);
  // Killed once the table shows it (discovery takes up to 3 s when a first
  // participant announcement is lost).
  REQUIRE(test::waitForText(watch_log, "\"component\":\"wheel_tach\"", 20, watch));
  rigs.tach->signal(SIGKILL);
  std::this_thread::sleep_for(std::chrono::milliseconds(4500));  // the 3 s lease and a table line
  watch.signal(SIGTERM);
  watch.wait(10);
  const std::string table = test::readFile(watch_log);
  INFO(table);
  const auto last_line = table.rfind("\n[", table.size() - 2);
  REQUIRE(last_line != std::string::npos);
  const auto rows = nlohmann::json::parse(table.substr(last_line + 1));
  bool tach_seen = false;
  for (const auto& row : rows) {
    if (row["component"] == "wheel_tach") {
      tach_seen = true;
      CHECK(row["alive"] == false);
    } else {
      CHECK(row["alive"] == true);
    }
  }
  CHECK(tach_seen);

  const int code = rigs.rig.wait(60);
  INFO(test::readFile(out + ".log"));  // read after the end: the launcher's reason is in it
  REQUIRE(code == 0);  // paced waits for nobody: the run completes
  const fs::path exported = fs::path(out) / "export";
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out +
                           "/recording.sqlite --json -t fault_event -t wheel_tach -t wheel_torque_cmd -o " +
                           exported.string())
              .exit_code == 0);
  // The attitude controller, a consumer of the tachometers, goes on with their last
  // sample (stale) for the 1 s lease after the kill, then, its producer dead, with
  // their missing form (a dropout): the loop never stops for a dead sensor.
  std::uint64_t last_tach = 0;
  for (const auto& s : test::exportedRows(exported, "wheel_tach")) {
    last_tach = std::max(last_tach, s["header"]["step"].get<std::uint64_t>());
  }
  std::uint64_t within_lease = 0, after_lease = 0;
  for (const auto& s : test::exportedRows(exported, "wheel_torque_cmd")) {
    const auto step = s["header"]["step"].get<std::uint64_t>();
    within_lease += step > last_tach && step <= last_tach + 10;
    after_lease += step > last_tach + 12;
  }
  CHECK(within_lease >= 8);
  CHECK(after_lease > 10);
  bool lost = false;
  for (const auto& event : test::exportedRows(exported, "fault_event")) {
    lost |= event["kind"] == "lost" && event["header"]["source"] == "wheel_tach" && event["active"] == true &&
            event["topic"] == "flatsat/health";
  }
  CHECK(lost);
  fs::remove_all(out);
  fs::remove(out + ".log");
  fs::remove(out + "-tach.log");
  fs::remove(out + "-health.log");
}

TEST_CASE("paced: a component whose steps stop is shown late within its deadline, recorded, and on time again",
          "[system][liveliness][paced]") {
  test::exportTestDomain();
  // A process stopped while it holds one of Fast DDS's interprocess locks
  // (shared-memory transport, data sharing) aborts the peer that waits on it
  // past 1 s: the rig goes over UDP on 127.0.0.1 only, as it must under a
  // debugger.
  const test::ScopedEnv no_shared_memory("FLATSAT_SHARED_MEMORY", "0");
  const std::string out = test::freshDir("late-paced");
  test::Background rig(test::kFlatsat + " run " + kDefault + " -q --no-plots --out " + out +
                           " --set mode=paced --set duration_orbits=null --set duration_s=15",
                       out + ".log");
  REQUIRE(test::waitForText(fs::path(out) / "logs" / "dynamics_server.log", "every component ready", 60, rig));
  const std::string watch_log = out + "-health.log";
  test::Background watch(test::kFlatsat + " health --json --every 0.2", watch_log);
  REQUIRE(test::waitForText(watch_log, "\"component\":\"gyro\"", 20, watch));
  std::this_thread::sleep_for(std::chrono::seconds(2));
  // SIGSTOP halts the whole process for 1.8 s: longer than the gyro topic's
  // 1 s deadline and kHealthLate (1.5 s), shorter than the 3 s health lease
  // less the 0.5 s between liveliness assertions, so it is late, not lost
  // (with 1 s between them a loaded machine once made it lost).
  const std::string gyro = "'flatsat-gyr[o] --scenario " + out + "/'";
  REQUIRE(test::runCommand("pkill -STOP -f " + gyro).exit_code == 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1800));
  REQUIRE(test::runCommand("pkill -CONT -f " + gyro).exit_code == 0);
  std::this_thread::sleep_for(std::chrono::seconds(2));
  watch.signal(SIGTERM);
  watch.wait(10);
  const int code = rig.wait(60);
  INFO(test::readFile(out + ".log"));  // read after the end: the launcher's reason is in it
  REQUIRE(code == 0);  // paced waits for nobody

  // The operator's table showed the gyro late, and only the gyro, while it stood still.
  std::stringstream table(test::readFile(watch_log));
  bool gyro_late = false, other_late = false, gyro_gone = false;
  for (std::string line; std::getline(table, line);) {
    if (line.empty() || line.front() != '[') continue;
    for (const auto& row : nlohmann::json::parse(line)) {
      const bool late = row["late"].get<bool>();
      (row["component"] == "gyro" ? gyro_late : other_late) |= late;
      gyro_gone |= row["component"] == "gyro" && !row["alive"].get<bool>();
    }
  }
  CHECK(gyro_late);
  CHECK_FALSE(other_late);
  CHECK_FALSE(gyro_gone);

  const fs::path exported = fs::path(out) / "export";
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -t fault_event -t health -o " +
                           exported.string())
              .exit_code == 0);
  std::uint64_t late_at = 0, on_time_at = 0;
  for (const auto& event : test::exportedRows(exported, "fault_event")) {
    if (event["kind"] != "late") continue;
    CHECK(event["header"]["source"] == "gyro");
    (event["active"] == true ? late_at : on_time_at) = event["header"]["step"].get<std::uint64_t>();
  }
  CHECK(late_at > 0);
  // Late 1.5 s after its last health at most ~1.1 s before the stop, on time
  // again within the second after SIGCONT: the stop is 18 steps.
  CHECK(on_time_at > late_at);
  CHECK(on_time_at - late_at <= 18);
  // Every consumer of the gyro counted at least one deadline of its topic.
  std::map<std::string, std::uint64_t> missed;
  for (const auto& health : test::exportedRows(exported, "health")) {
    missed[health["header"]["source"].get<std::string>()] = health["deadlines_missed"].get<std::uint64_t>();
  }
  CHECK(missed["estimator"] >= 1);
  CHECK(test::readFile(fs::path(out) / "logs" / "estimator.log").find("flatsat/gyro from gyro is late") !=
        std::string::npos);
  // ... and nothing else missed one: the 1 Hz unloading commands, slower than the 1 s
  // lease, are watched at one and a half of their own period.
  const auto total_missed = test::readSummary(out)["deadlines_missed"].get<std::uint64_t>();
  CHECK(total_missed >= 1);
  CHECK(total_missed <= 2 * missed["estimator"] + 2);
  CHECK(test::readFile(out + ".log").find("gyro is late at step") != std::string::npos);
  fs::remove_all(out);
  fs::remove(out + ".log");
  fs::remove(watch_log);
}

namespace {

/// The rows of `topic` stamped before `step` and from it on.
std::pair<std::vector<nlohmann::json>, std::vector<nlohmann::json>> splitAt(const std::vector<nlohmann::json>& rows,
                                                                             std::uint64_t step) {
  std::pair<std::vector<nlohmann::json>, std::vector<nlohmann::json>> split;
  for (const auto& row : rows) {
    (row["header"]["step"].get<std::uint64_t>() < step ? split.first : split.second).push_back(row);
  }
  return split;
}

/// Runs `scenario` paced with --restart, SIGKILLs `victim` after `kill_after_s`, and
/// returns the step its restart was recorded at (0: none) with the run's export of `topic`.
std::uint64_t killAndRestart(const std::string& scenario, const std::string& out, const std::string& victim,
                             double duration_s, double kill_after_s, const std::string& topic,
                             std::vector<nlohmann::json>& rows, const std::string& extra = "") {
  test::Background rig(test::kFlatsat + " run " + scenario + " -q --no-plots --restart --out " + out +
                           " --set mode=paced --set duration_orbits=null --set duration_s=" +
                           std::to_string(duration_s) + " " + extra,
                       out + ".log");
  REQUIRE(test::waitForText(fs::path(out) / "logs" / "dynamics_server.log", "every component ready", 60, rig));
  std::this_thread::sleep_for(std::chrono::duration<double>(kill_after_s));
  // [x] in the pattern: pkill's own shell command line does not match it.
  const std::string pattern = "flatsat-" + victim.substr(0, victim.size() - 1) + "[" + victim.back() + "]";
  REQUIRE(test::runCommand("pkill -KILL -f '" + pattern + " --scenario " + out + "/'").exit_code == 0);
  INFO(test::readFile(out + ".log"));
  REQUIRE(rig.wait(90) == 0);  // the rig ran to its end around the restart

  const auto summary = test::readSummary(out);
  CHECK(summary["restarts"][victim] == 1);
  const std::string restart_log = test::readFile(fs::path(out) / "logs" / (victim + ".restart-1.log"));
  INFO(restart_log);
  CHECK(restart_log.find(victim + ": ready") != std::string::npos);
  CHECK(restart_log.find(victim + ": restarted with the state it had after step") != std::string::npos);
  const fs::path exported = fs::path(out) / "export";
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -t fault_event -t " + topic +
                           " -o " + exported.string())
              .exit_code == 0);
  std::uint64_t restarted_at = 0;
  for (const auto& event : test::exportedRows(exported, "fault_event")) {
    if (event["kind"] == "restarted" && event["header"]["source"] == victim) {
      restarted_at = event["header"]["step"].get<std::uint64_t>();
    }
  }
  rows = test::exportedRows(exported, topic);
  return restarted_at;
}

double attitudeVariance(const nlohmann::json& estimate) {
  const auto& p = estimate["attitude_cov_body_rad2"];
  return p[0].get<double>() + p[4].get<double>() + p[8].get<double>();
}

}  // namespace

TEST_CASE("paced --restart: a killed estimator is started again, rejoins with its estimate, and it is recorded",
          "[system][liveliness][paced][restart]") {
  test::exportTestDomain();
  const std::string out = test::freshDir("restart-estimator");
  std::vector<nlohmann::json> estimates;
  const std::uint64_t restarted_at = killAndRestart(std::string(FLATSAT_SCENARIO_DIR) + "/mekf.yaml", out, "estimator",
                                                    20, 5, "attitude_estimate", estimates);
  REQUIRE(restarted_at > 0);
  const auto [before, after] = splitAt(estimates, restarted_at);
  REQUIRE(before.size() > 20);
  REQUIRE(after.size() > 50);
  // The new process publishes on the same topic until the end of the run.
  CHECK(after.back()["header"]["step"].get<std::uint64_t>() >= 190);
  // A fresh MEKF starts from its initial 0.5° per axis and acquires again; the restarted
  // one goes on from its last covariance, grown only over the steps it missed.
  const double initial = attitudeVariance(before.front());
  const double last_before = attitudeVariance(before.back());
  const double first_after = attitudeVariance(after.front());
  INFO("attitude variance [rad²]: initial " << initial << ", before the kill " << last_before
                                          << ", first after the restart " << first_after);
  REQUIRE(last_before < 0.1 * initial);
  CHECK(after.front()["initialized"] == true);
  CHECK(first_after < 0.5 * initial);
  CHECK(first_after < 3.0 * last_before);
  CHECK(after.front()["measurements_rejected"].get<std::uint64_t>() >=
        before.back()["measurements_rejected"].get<std::uint64_t>());
  fs::remove_all(out);
  fs::remove(out + ".log");
}

TEST_CASE("paced --restart: a killed thruster sequencer goes on counting the correction it was in",
          "[system][liveliness][paced][restart]") {
  test::exportTestDomain();
  const std::string out = test::freshDir("restart-sequencer");
  std::vector<nlohmann::json> commands;
  // T1 = 2 s: n counts a pulse every 2 s while the angle stays outside.
  const std::uint64_t restarted_at =
      killAndRestart(std::string(FLATSAT_SCENARIO_DIR) + "/s1_example.yaml", out, "thruster_sequencer", 14, 7.5,
                     "thruster_cmd", commands, "--set components.thruster_sequencer.correction_interval_s=2");
  REQUIRE(restarted_at > 0);
  const auto [before, after] = splitAt(commands, restarted_at);
  REQUIRE(!before.empty());
  REQUIRE(!after.empty());
  const auto n_before = before.back()["correction_count"].get<int>();
  INFO("n before the kill " << n_before << ", first after the restart " << after.front()["correction_count"]);
  REQUIRE(n_before >= 2);
  REQUIRE(before.back()["phase"] == 1);  // correcting
  // A fresh sequencer would be acquiring with n = 0; the restarted one still corrects and
  // counts on from its n.
  CHECK(after.front()["phase"] == 1);
  CHECK(after.front()["correction_count"].get<int>() >= n_before);
  CHECK(after.back()["correction_count"].get<int>() > n_before);
  fs::remove_all(out);
  fs::remove(out + ".log");
}

TEST_CASE("flatsat run --restart is refused where a component cannot be started again", "[system][liveliness]") {
  const auto lockstep = test::runCommand(test::kFlatsat + " run " + kDefault + " -q --no-plots --restart --out " +
                                         test::freshDir("restart-lockstep"));
  CHECK(lockstep.exit_code == 2);
  CHECK(lockstep.output.find("only a paced multi-process run") != std::string::npos);
}
