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
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/Background.hpp"
#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

const std::string kDefault = std::string(FLATSAT_SCENARIO_DIR) + "/default.yaml";

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
  std::this_thread::sleep_for(std::chrono::seconds(3));
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

  INFO(test::readFile(out + ".log"));
  REQUIRE(rigs.rig.wait(60) == 0);  // paced waits for nobody: the run completes
  const fs::path exported = fs::path(out) / "export";
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -t fault_event -o " +
                           exported.string())
              .exit_code == 0);
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

TEST_CASE("paced --restart: a killed component is started again, rejoins, and the restart is recorded",
          "[system][liveliness][paced]") {
  test::exportTestDomain();
  const std::string out = test::freshDir("restart");
  test::Background rig(test::kFlatsat + " run " + kDefault + " -q --no-plots --restart --out " + out +
                           " --set mode=paced --set duration_orbits=null --set duration_s=20",
                       out + ".log");
  REQUIRE(test::waitForText(fs::path(out) / "logs" / "dynamics_server.log", "every component ready", 60, rig));
  std::this_thread::sleep_for(std::chrono::seconds(4));
  REQUIRE(test::runCommand("pkill -KILL -f 'flatsat-gyr[o] --scenario " + out + "/'").exit_code == 0);
  INFO(test::readFile(out + ".log"));
  REQUIRE(rig.wait(90) == 0);  // the rig ran to its end around the restart

  const auto summary = test::readSummary(out);
  CHECK(summary["restarts"]["gyro"] == 1);
  CHECK(test::readFile(fs::path(out) / "logs" / "gyro.restart-1.log").find("gyro: ready") != std::string::npos);
  const fs::path exported = fs::path(out) / "export";
  REQUIRE(test::runCommand(test::kFlatsat + " export " + out + "/recording.sqlite --json -t fault_event -t gyro -o " +
                           exported.string())
              .exit_code == 0);
  std::uint64_t restarted_at = 0;
  for (const auto& event : test::exportedRows(exported, "fault_event")) {
    if (event["kind"] == "restarted" && event["header"]["source"] == "gyro") {
      restarted_at = event["header"]["step"].get<std::uint64_t>();
    }
  }
  CHECK(restarted_at > 0);
  // The new process publishes on the same topic until the end of the run.
  std::uint64_t after = 0, last = 0;
  for (const auto& sample : test::exportedRows(exported, "gyro")) {
    const auto step = sample["header"]["step"].get<std::uint64_t>();
    after += step > restarted_at + 20;
    last = std::max(last, step);
  }
  CHECK(after > 50);
  CHECK(last >= 190);
  fs::remove_all(out);
  fs::remove(out + ".log");
}

TEST_CASE("flatsat run --restart is refused where a component cannot be started again", "[system][liveliness]") {
  const auto lockstep = test::runCommand(test::kFlatsat + " run " + kDefault + " -q --no-plots --restart --out " +
                                         test::freshDir("restart-lockstep"));
  CHECK(lockstep.exit_code == 2);
  CHECK(lockstep.output.find("only a paced multi-process run") != std::string::npos);
}
