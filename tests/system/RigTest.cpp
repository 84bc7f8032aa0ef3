// SPDX-License-Identifier: Apache-2.0
// The whole rig: every component its own process, lockstep over DDS on
// loopback, judged on the recorded truth.
#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <thread>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/support/Background.hpp"
#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"
#include "tests/support/TestDomain.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

using test::kFlatsat;
using test::kDefault;

using test::freshDir;

test::RigRun runRig(const std::string& out, const std::string& extra) {
  return test::runScenario(kDefault, out, extra);
}

}  // namespace

TEST_CASE("default rig closes the loop: Sun pointing held, momentum unloaded",
          "[system][slow]") {
  // One orbit after the initial slew (acquisition at 1500 s): the long-run bound and the
  // comparison with unloading off are UnloadingTest's (10 orbits).
  const auto on = runRig(freshDir("on"), "--set duration_orbits=1");
  INFO(on.summary.dump(2));
  CHECK(on.summary["processes"].get<int>() >= 8);
  CHECK(on.summary["steps"].get<double>() >= 5700 / 0.1);  // an orbit at 560 km
  CHECK(on.summary["pointing_error_deg_max"].get<double>() < 0.5);
  const double capacity = on.summary["wheel_capacity_Nms"].get<double>();
  CHECK(on.summary["wheel_momentum_Nms_max"].get<double>() < 0.2 * capacity);
  CHECK(on.summary["wheel_saturation_events"].get<int>() == 0);
}

TEST_CASE("two runs of a scenario record bit-identical samples", "[system]") {
  const std::string args = "--set duration_orbits=null --set duration_s=200";
  const auto first = runRig(freshDir("det1"), args);
  const auto second = runRig(freshDir("det2"), args);
  CHECK(first.summary["steps"] == 2001);
  CHECK(first.summary["recording_sha256"].get<std::string>().size() == 64);
  CHECK(first.summary["recording_sha256"] == second.summary["recording_sha256"]);
}

TEST_CASE("a bad scenario is refused before any process starts, naming file, key and reason",
          "[system]") {
  const std::string dir = std::string(FLATSAT_TEST_SCENARIO_DIR);
  const std::string out = freshDir("bad");
  struct Case {
    std::string file, expected_key, expected_reason;
  };
  const Case cases[] = {
      {"unknown_key.yaml", "components.gyro.noise_density", "unknown key"},
      {"wrong_unit.yaml", "orbit.altitude_m", "wrong unit 's'"},
      {"missing_igrf.yaml", "environment.igrf_file", "cannot open"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.file);
    const auto result = test::runCommand(kFlatsat + " run " + dir + "/" + c.file + " --out " + out);
    INFO(result.output);
    CHECK(result.exit_code == 2);
    CHECK(result.output.find(c.file + ":") != std::string::npos);  // file:line:col
    CHECK(result.output.find(c.expected_key) != std::string::npos);
    CHECK(result.output.find(c.expected_reason) != std::string::npos);
    CHECK_FALSE(fs::exists(fs::path(out) / "logs"));  // nothing was started
  }
  // validate (alias check) says the same without running anything, at the key's line.
  const auto validated = test::runCommand(kFlatsat + " validate " + dir + "/unknown_key.yaml");
  INFO(validated.output);
  CHECK(validated.exit_code == 2);
  std::istringstream fixture(test::readFile(dir + "/unknown_key.yaml"));
  int line = 0, key_line = 0;
  for (std::string text; std::getline(fixture, text);) {
    ++line;
    if (text.find("noise_density:") != std::string::npos) key_line = line;
  }
  REQUIRE(key_line > 0);
  CHECK(validated.output.find("unknown_key.yaml:" + std::to_string(key_line) + ":") != std::string::npos);
  for (const auto& scenario : fs::directory_iterator(FLATSAT_SCENARIO_DIR)) {
    const auto ok = test::runCommand(kFlatsat + " validate " + scenario.path().string());
    CAPTURE(scenario.path(), ok.output);
    CHECK(ok.exit_code == 0);
  }
  const auto missing = test::runCommand(kFlatsat + " run " + dir + "/no_such_file.yaml");
  CHECK(missing.exit_code == 2);
  CHECK(missing.output.find("no_such_file.yaml: no such file") != std::string::npos);
}

TEST_CASE("a component that dies stops the run, and the launcher says which", "[system]") {
  test::exportTestDomain();
  const std::string out = freshDir("kill");
  // The launcher runs in the background; the gyro is killed once stepping.
  const std::string script = out + ".sh";
  std::ofstream(script)
      << "(" << kFlatsat << " run " << kDefault << " -q --out " << out << " > " << out
      << ".log 2>&1; echo $? > " << out << ".rc) &\n"
      << "for i in $(seq 1 300); do\n"
      << "  grep -q ready " << out << "/logs/gyro.log 2>/dev/null && break; sleep 0.1\n"
      << "done\nsleep 2\n"
      << "pkill -KILL -f 'flatsat-gyro --scenario " << out << "/'\n"
      << "wait\ncat " << out << ".rc " << out << ".log\n";
  const auto result = test::runCommand("bash " + script);
  INFO(result.output);
  CHECK(result.output.rfind("1\n", 0) == 0);  // the launcher's exit code
  CHECK(result.output.find("component 'gyro' died (killed by signal 9)") != std::string::npos);
}

TEST_CASE("Ctrl-C on a run exits 130, keeps its summary with the step reached, and says how to resume",
          "[system]") {
  test::exportTestDomain();
  const std::string out = freshDir("interrupted");
  const std::string log = out + ".log";
  const pid_t run = test::startCommand(kFlatsat + " run " + kDefault + " --no-plots --out " + out +
                                           " --set duration_orbits=1",
                                       log);
  // Interrupted once the recorder holds some steps.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline &&
         test::readFile(log).find("steps/s") == std::string::npos) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ::kill(run, SIGINT);
  const int exit_code = test::waitCommand(run);
  const std::string output = test::readFile(log);
  INFO(output);
  CHECK(exit_code == 130);
  nlohmann::json summary;
  std::ifstream(fs::path(out) / "summary.json") >> summary;
  CHECK(summary["completed"] == false);
  REQUIRE(summary["steps"].get<std::uint64_t>() > 0);
  CHECK(output.find("flatsat: interrupted; the recording holds steps 0.." +
                    std::to_string(summary["steps"].get<std::uint64_t>() - 1)) != std::string::npos);
  CHECK(output.find("flatsat run " + kDefault + " --resume " + out) != std::string::npos);
  // The operator's stop is no component's error, nor the tool's.
  CHECK(test::readFile(out + "/logs/recorder.log").find("[error]") == std::string::npos);
  CHECK(output.find("error:") == std::string::npos);
  fs::remove_all(out);
  fs::remove(log);
}
