// SPDX-License-Identifier: Apache-2.0
// A rogue participant writes samples that do not decode to every topic of a
// running lockstep rig: no process dies, the run completes, every component
// counts drops in its health, and the recording is bit-identical to a run
// without the rogue (nothing it sent got in).
#include <signal.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <catch2/catch.hpp>

#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"
#include "tests/support/TestDomain.hpp"

using namespace flatsat;

namespace {

using test::kDefault;
const std::string kRogue = std::string(FLATSAT_BIN_DIR) + "/rogue_participant";
// Long enough (a few seconds of stepping) for the 1 s health heartbeats to
// carry the counts into the recording.
const std::string kShort = "--set duration_orbits=null --set duration_s=600";

}  // namespace

TEST_CASE("a rogue writing malformed samples to every topic kills no process",
          "[system][malformed]") {
  test::exportTestDomain();
  // The rig takes the rogue for a producer (FLATSAT_TRUST, inherited by every
  // process): what is tried here is each decoder, not the trust a stranger
  // on a stepped topic meets, which ends a lockstep run at once (TrustTest).
  ::setenv("FLATSAT_TRUST", "rogue", 1);
  const std::string log = test::freshDir("rogue") + ".log";
  int rogue_exit = -1;
  test::RigRun attacked;
  {
    // On the test's domain; stopped (SIGTERM) however the run ends.
    const pid_t rogue = test::startCommand(kRogue + " 300", log);
    struct Stop {
      pid_t pid;
      int& exit_code;
      ~Stop() {
        ::kill(pid, SIGTERM);
        exit_code = test::waitCommand(pid);
      }
    } stop{rogue, rogue_exit};
    attacked = test::runScenario(kDefault, test::freshDir("attacked"), kShort);
  }
  ::unsetenv("FLATSAT_TRUST");
  CHECK(rogue_exit == 0);  // it was still writing when the run ended, and ended cleanly
  std::stringstream rogue_output;
  rogue_output << std::ifstream(log).rdbuf();
  std::filesystem::remove(log);
  INFO(rogue_output.str());
  REQUIRE(rogue_output.str().find("rogue: wrote") != std::string::npos);

  const auto& s = attacked.summary;
  INFO(s.dump(2));
  CHECK(s["steps"] == 6001);
  CHECK(s["samples_dropped"].get<std::uint64_t>() > 0);
  // Every component reads the step grants the rogue floods, so each one's
  // last recorded health counts drops.
  for (const auto& [component, role] : s["roles"].items()) {
    INFO(component);
    REQUIRE(s["samples_dropped_by_component"].contains(component));
    CHECK(s["samples_dropped_by_component"][component].get<std::uint64_t>() > 0);
  }
  const auto clean = test::runScenario(kDefault, test::freshDir("clean"), kShort);
  CHECK(clean.summary["samples_dropped"] == 0);
  CHECK(s["recording_sha256"] == clean.summary["recording_sha256"]);
}
