// SPDX-License-Identifier: Apache-2.0
// The whole rig with DDS Security on (`flatsat run --secure DIR`, certificates
// from deploy/security/make-certs.sh): it computes exactly what the open rig
// computes, a stolen component key writes nothing but that component's
// topics, and a command reaches it only from a tool holding the operator's
// certificate.
#include <catch2/catch.hpp>

#include <filesystem>

#include "tests/support/Background.hpp"
#include "tests/support/Certificates.hpp"
#include "tests/support/Rig.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

const std::string kShortRun = " --set duration_orbits=null --set duration_s=60";

}  // namespace

TEST_CASE("a secured rig records exactly what the open rig records, whatever a stolen component key tries",
          "[system][security][trust]") {
  const test::Certificates certs;
  test::exportTestDomain();
  const std::string scenario = std::string(FLATSAT_SCENARIO_DIR) + "/default.yaml";
  const auto open = test::runScenario(scenario, test::freshDir("open"), kShortRun);
  const std::string out = test::freshDir("secured");
  {
    test::Background rig(test::runLine(scenario, out, kShortRun + " --secure " + certs.dir.string()),
                         out + ".log");
    REQUIRE(test::waitForText(fs::path(out) / "logs" / "dynamics_server.log", "every component ready", 120, rig));
    // The gyro's key in a hostile program: its grant lets it write neither a
    // grant (a forged stop) nor another box's command.
    const std::string stolen = "env FLATSAT_SECURE_DIR=" + certs.dir.string() + " " + test::kHostile;
    const auto stop = test::runCommand(stolen + " forge-stop 5 gyro 2>&1");
    INFO(stop.output);
    CHECK(stop.exit_code == 3);
    CHECK(stop.output.find("hostile: forge-stop refused: could not create a writer on flatsat/step_grant") !=
          std::string::npos);
    const auto dipole = test::runCommand(stolen + " huge-dipole 5 gyro 2>&1");
    INFO(dipole.output);
    CHECK(dipole.exit_code == 3);
    CHECK(dipole.output.find("could not create a writer on flatsat/dipole_cmd") != std::string::npos);
    INFO(test::readFile(out + ".log"));
    REQUIRE(rig.wait(600) == 0);
  }
  const auto secured = test::readSummary(out);
  CHECK(secured["completed"] == true);
  CHECK(secured["intruders"] == 0);
  CHECK(secured["steps"] == open.summary["steps"]);
  CHECK(secured["recording_sha256"] == open.summary["recording_sha256"]);
  fs::remove_all(out);
  fs::remove(out + ".log");
}

TEST_CASE("a secured rig takes commands only from a tool with the operator's certificate, and runs its "
          "hardware bridges",
          "[system][security][cmd][hil]") {
  // hil_reaction_wheel.yaml: the default rig, paced, with a reaction wheel unit behind its
  // bridge. The bridge and the unit's stand-in are process-only kinds: their grants come
  // from the registry's list of what they read (the grants, the wheel commands, the
  // truth, bus faults).
  const test::Certificates certs;
  test::exportTestDomain();
  const std::string run = test::freshDir("secure-cmd");
  test::Background rig(test::kFlatsat + " run " + std::string(FLATSAT_SCENARIO_DIR) +
                           "/hil_reaction_wheel.yaml -q --no-plots --out " + run +
                           // Long enough for the stranger's 4 s and the operator's two 4 s tries
                           // after the start: under a loaded suite the run had ended before an ack.
                           " --set mode=paced --set duration_orbits=null --set duration_s=20" +
                           " --secure " + certs.dir.string(),
                       run + ".log");
  REQUIRE(test::waitForText(fs::path(run) / "logs" / "dynamics_server.log",
                            "every component ready", 120, rig));
  const std::string fault = test::kFlatsat + " cmd fault gyro bias --magnitude 1e-4 --timeout 4";
  const auto stranger = test::runCommand(fault + " 2>&1");
  INFO(stranger.output);
  CHECK(stranger.exit_code == 1);  // no acknowledgement: nobody heard it
  const auto operator_cmd = test::runCommand("FLATSAT_SECURE_DIR=" + certs.dir.string() + " " + fault + " 2>&1");
  INFO(operator_cmd.output);
  CHECK(operator_cmd.exit_code == 0);
  CHECK(operator_cmd.output.find("accepted by gyro") != std::string::npos);
  INFO(test::readFile(run + ".log"));
  REQUIRE(rig.wait(60) == 0);
  const auto s = test::readSummary(run);
  CHECK(s["topic_producers"]["flatsat/wheel_tach"] == nlohmann::json::array({"wheel_tach", "wheel_tach_bridge"}));
  CHECK(s["ownership_switches"].size() == 1);  // to the bridge, and never back
  for (const std::string process : {"wheel_tach_bridge", "wheel_tach_device"}) {
    const std::string log = test::readFile(run + "/logs/" + process + ".log");
    INFO(log);
    CHECK(log.find("[error]") == std::string::npos);
  }
  CHECK(test::readFile(run + "/logs/dynamics_server.log").find("the wheels follow the unit behind wheel_tach_bridge") !=
        std::string::npos);
  fs::remove_all(run);
  fs::remove(run + ".log");
}

