// SPDX-License-Identifier: Apache-2.0
// `flatsat run --composed`: the same components in one process on an
// in-process bus record exactly what the multi-process lockstep rig records,
// faster, without a DDS participant.
#include <catch2/catch.hpp>

#include <sys/types.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/Background.hpp"
#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

using test::kDefault;
const std::string kShort = "--set duration_orbits=null --set duration_s=300";

/// What a live process holds that a DDS participant would have opened:
/// sockets (UDP transport, discovery) and /dev/shm mappings (SHM transport,
/// data sharing). Empty when it holds neither (or is gone).
std::string networkResources(pid_t pid) {
  std::string found;
  const fs::path fd_dir = "/proc/" + std::to_string(pid) + "/fd";
  std::error_code ec;
  for (const auto& fd : fs::directory_iterator(fd_dir, ec)) {
    const auto target = fs::read_symlink(fd.path(), ec);
    if (!ec && (target.string().rfind("socket:", 0) == 0 || target.string().rfind("/dev/shm/", 0) == 0)) {
      found += " fd " + target.string();
    }
  }
  std::ifstream maps("/proc/" + std::to_string(pid) + "/maps");
  for (std::string line; std::getline(maps, line);) {
    if (line.find("/dev/shm/") != std::string::npos) found += " map " + line.substr(line.rfind(' ') + 1);
  }
  return found;
}

}  // namespace

TEST_CASE("a composed run records what the multi-process rig records, faster, without DDS",
          "[system][composed]") {
  const std::string multi = test::freshDir("multi");
  const auto processes = test::runScenario(kDefault, multi, kShort, true);
  {
    // The launcher started every process here: each scheduled component reads
    // best-effort (QosTuning::best_effort_readers) and the rig still records the same.
    for (const char* component : {"recorder", "estimator", "gyro", "attitude_controller"}) {
      CAPTURE(component);
      CHECK(test::readFile(multi + "/logs/" + component + ".log").find("readers best-effort") != std::string::npos);
    }
    fs::remove_all(multi);
  }

  // The composed run in the background, watched while it runs: it must
  // never hold a socket or a shared-memory segment.
  const std::string out = test::freshDir("composed");
  const std::string log = out + ".log";
  const pid_t pid = test::startCommand(
      test::kFlatsat + " run " + kDefault + " --composed -q --no-plots --out " + out + " " + kShort, log);
  int looks = 0;
  std::string held;
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) {
      INFO(std::ifstream(log).rdbuf());
      REQUIRE((WIFEXITED(status) && WEXITSTATUS(status) == 0));
      break;
    }
    held += networkResources(pid);
    ++looks;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  fs::remove(log);
  const auto composed = test::readSummary(out);
  fs::remove_all(out);

  INFO("looked " << looks << " times while it ran");
  CHECK(looks >= 10);  // the run lasts well over 20 ms: the looks saw it running
  CHECK(held.empty());
  const double multi_rate = processes.summary["steps_per_second"].get<double>();
  const double composed_rate = composed["steps_per_second"].get<double>();
  std::printf("multi-process: %.0f steps/s (x%.0f real time), composed: %.0f steps/s (x%.0f)\n",
              multi_rate, processes.summary["speed_factor"].get<double>(), composed_rate,
              composed["speed_factor"].get<double>());
  CHECK(composed["processes"] == 1);
  CHECK(composed["steps"] == 3001);
  CHECK(composed["steps"] == processes.summary["steps"]);
  CHECK(composed["recording_sha256"].get<std::string>().size() == 64);
  CHECK(composed["recording_sha256"] == processes.summary["recording_sha256"]);
  CHECK(composed_rate >= multi_rate);
}

TEST_CASE("a scenario a composed rig cannot hold is refused, naming the component and reason",
          "[system][composed]") {
  const std::string out = test::freshDir("composed-hil");
  const auto run = test::runCommand(test::kFlatsat + " run " + std::string(FLATSAT_SCENARIO_DIR) +
                                    "/hil_magnetometer.yaml --composed -q --no-plots --out " + out);
  INFO(run.output);
  CHECK(run.exit_code == 2);
  CHECK(run.output.find("mode: paced") != std::string::npos);
  CHECK(run.output.find("components.magnetometer_bridge: a hardware bridge") != std::string::npos);
  CHECK(run.output.find("components.magnetometer_device: a device stand-in") != std::string::npos);
  CHECK_FALSE(fs::exists(out));

  const auto lockstep = test::runCommand(
      test::kFlatsat + " run " + std::string(FLATSAT_SCENARIO_DIR) +
      "/hil_magnetometer.yaml --composed -q --no-plots --set mode=lockstep --out " + out);
  INFO(lockstep.output);
  CHECK(lockstep.exit_code == 2);
  CHECK(lockstep.output.find("mode: paced") == std::string::npos);
  CHECK(lockstep.output.find("components.magnetometer_bridge") != std::string::npos);
  CHECK_FALSE(fs::exists(out));

  const auto external = test::runCommand(test::kFlatsat + " run " + kDefault +
                                         " --composed -q --no-plots --set components.gyro.role=external --out " + out);
  INFO(external.output);
  CHECK(external.exit_code == 2);
  CHECK(external.output.find("default.yaml: components.gyro: role: external") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("every closed-loop scenario records the same composed as over the bus",
          "[system][composed]") {
  // The long verification runs (S0, MEKF, unloading, B-dot, S4, S2, thruster dumping, S1) go
  // composed; here each of their scenarios shows the two rigs agree to the bit, over a
  // stretch that holds every component's first outputs and the loops' first actions.
  const std::string dir = std::string(FLATSAT_SCENARIO_DIR) + "/";
  for (const std::string name : {"s0_no_magnetometer", "mekf", "mekf_star_tracker",
                                 "unloading_10orbits", "detumble", "s4_spin", "s2_aero", "thruster_dumping",
                                 "s1_example"}) {
    const std::string scenario = dir + name + ".yaml";
    const std::string shorter = "--set duration_orbits=null --set duration_s=120";
    const auto processes = test::runScenario(scenario, test::freshDir("multi-" + name), shorter);
    const auto composed =
        test::runScenario(scenario, test::freshDir("composed-" + name), shorter + " --composed");
    CAPTURE(name);
    CHECK(composed.summary["steps"] == processes.summary["steps"]);
    CHECK(composed.summary["recording_sha256"] == processes.summary["recording_sha256"]);
  }
}
