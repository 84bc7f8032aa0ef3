// SPDX-License-Identifier: Apache-2.0
// The operator tools against a real rig: topics, echo, hz and health look at
// a rig running in the background (paced, so rates are known); export and
// plot read the recording of a finished run.
#include <catch2/catch.hpp>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <climits>
#include <map>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"
#include "tests/support/TestDomain.hpp"

extern char** environ;

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

using test::kFlatsat;
using test::kDefault;
/// The default rig's components (deploy/scenarios/default.yaml).
const std::vector<std::string> kComponents = {
    "dynamics_server", "magnetometer",        "sun_sensor",           "gyro",    "wheel_tach",
    "estimator",       "attitude_controller", "unloading_controller", "recorder"};

std::string freshDir(const std::string& tag) {
  const fs::path dir =
      fs::temp_directory_path() / ("flatsat-tools-" + tag + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir.string();
}

std::string readFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The default rig running paced (10 Hz truth, 1 Hz dipole) in the
/// background for a live tool to look at; stopped with SIGTERM to the
/// launcher when the test ends.
class BackgroundRig {
 public:
  explicit BackgroundRig(const std::string& tag) : dir_(freshDir(tag)) {
    test::exportTestDomain();
    const std::string command = "exec " + kFlatsat + " run " + kDefault + " -q --out " + dir_ +
                                " --set mode=paced --set duration_orbits=null"
                                " --set duration_s=900 > " + dir_ + ".log 2>&1";
    const char* argv[] = {"/bin/sh", "-c", command.c_str(), nullptr};
    REQUIRE(::posix_spawn(&pid_, "/bin/sh", nullptr, nullptr, const_cast<char**>(argv), environ) == 0);
    // Stepping once the time master says so.
    const fs::path log = fs::path(dir_) / "logs" / "dynamics_server.log";
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (readFile(log).find("every component ready") == std::string::npos) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        FAIL("the rig exited before stepping:\n" << readFile(dir_ + ".log"));
      }
      if (std::chrono::steady_clock::now() > deadline) FAIL("the rig did not start stepping in 120 s");
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
  }
  ~BackgroundRig() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
    fs::remove_all(dir_);
    fs::remove(dir_ + ".log");
  }
  BackgroundRig(const BackgroundRig&) = delete;
  BackgroundRig& operator=(const BackgroundRig&) = delete;

 private:
  std::string dir_;
  pid_t pid_ = -1;
};

/// A finished lockstep run of 60 simulated seconds (601 steps); its folder.
std::string finishedRun(const std::string& tag) {
  test::exportTestDomain();
  const std::string dir = freshDir(tag);
  const auto run = test::runCommand(kFlatsat + " run " + kDefault + " -q --no-plots --out " + dir +
                                    " --set duration_orbits=null --set duration_s=60");
  INFO(run.output);
  REQUIRE(run.exit_code == 0);
  return dir;
}

/// Every JSON document in a stream of (pretty) JSON documents.
std::vector<nlohmann::json> parseDocuments(const std::string& text) {
  std::vector<nlohmann::json> docs;
  std::istringstream in(text);
  while (in >> std::ws && in.peek() != EOF) {
    nlohmann::json doc;
    in >> doc;
    docs.push_back(doc);
  }
  return docs;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// stdout only: the tools report progress on stderr.
test::CommandResult tool(const std::string& args) {
  return test::runCommand("(" + kFlatsat + " " + args + " 2>/dev/null)");
}

}  // namespace

TEST_CASE("every tool subcommand explains itself with --help", "[system][tools]") {
  for (const std::string command :
       {"topics", "echo", "hz", "health", "export", "info", "plot", "record", "replay", "cmd"}) {
    CAPTURE(command);
    const auto help = test::runCommand(kFlatsat + " " + command + " --help");
    INFO(help.output);
    CHECK(help.exit_code == 0);
    CHECK(help.output.find("Usage:") != std::string::npos);
    CHECK((help.output.find("--domain") != std::string::npos ||
           help.output.find("recording") != std::string::npos));
  }
}

TEST_CASE("a command-line error exits 2 with the error and the command's usage, and an unknown command is named",
          "[system][tools]") {
  struct Case {
    std::string args, says, usage;
  };
  for (const auto& c : {Case{"frobnicate", "error: unknown command 'frobnicate'; the commands: run, check,", ""},
                        Case{"", "error: A subcommand is required", "Usage: flatsat [OPTIONS] SUBCOMMAND"},
                        Case{"run", "error: scenario is required", "Usage: flatsat run [OPTIONS] scenario"},
                        Case{"export x --csv --json", "error: --csv excludes --json", "Usage: flatsat export"},
                        Case{"mc --runs", "error: --runs: 1 required INT missing", "Usage: flatsat mc"},
                        Case{"info --no-such-flag x", "error: The following argument was not expected: --no-such-flag",
                             "Usage: flatsat info"},
                        Case{"rn default", "error: unknown command 'rn' (did you mean 'run'?)", ""},
                        Case{"run nonesuch", "nonesuch: no such file here, and no scenario of that name in ",
                             "Usage: flatsat run [OPTIONS] scenario"}}) {
    CAPTURE(c.args);
    const auto result = test::runCommand(kFlatsat + " " + c.args);
    INFO(result.output);
    CHECK(result.exit_code == 2);
    CHECK(result.output.find(c.says) != std::string::npos);
    CHECK(result.output.find(c.usage) != std::string::npos);
  }
  const auto version = test::runCommand(kFlatsat + " --version");
  CHECK(version.exit_code == 0);
  CHECK(version.output.rfind("0.1.0", 0) == 0);
  // A component's own command line too.
  const auto component = test::runCommand(std::string(FLATSAT_BIN_DIR) + "/flatsat-gyro --no-such-flag");
  INFO(component.output);
  CHECK(component.exit_code == 2);
  CHECK(test::runCommand(std::string(FLATSAT_BIN_DIR) + "/flatsat-gyro --version").output == version.output);
}

TEST_CASE("a scenario is named as flatsat scenarios lists it, and check places each problem at its line",
          "[system][tools]") {
  const auto listed = test::runCommand(kFlatsat + " scenarios");
  INFO(listed.output);
  CHECK(listed.exit_code == 0);
  CHECK(listed.output.find("  default                      ROSAT-like Sun pointing") != std::string::npos);
  const auto by_name = test::runCommand(kFlatsat + " check default");
  INFO(by_name.output);
  CHECK(by_name.exit_code == 0);
  CHECK(by_name.output.find("/share/flatsat/scenarios/default.yaml: ok (9 components)") != std::string::npos);

  const std::string dir = test::freshDir("check-places");
  fs::create_directories(dir);
  const std::string mine = dir + "/mine.yaml";
  std::ofstream(mine) << "base: default\nname: mine\ncomponents:\n  gyroo: {}\n";
  const auto typo = test::runCommand(kFlatsat + " check " + mine);
  INFO(typo.output);
  CHECK(typo.exit_code == 2);
  CHECK(typo.output.find(mine + ":4:10: components.gyroo: unknown component (did you mean 'gyro'?)") !=
        std::string::npos);
  const auto both = test::runCommand(kFlatsat + " validate default --set duration_s=10");
  INFO(both.output);
  CHECK(both.exit_code == 2);
  CHECK(both.output.find("--set duration_s=10: duration_s: give duration_s or duration_orbits, not both (to run by "
                         "time, also set `duration_orbits: null`, or --set duration_orbits=null)") != std::string::npos);
  const auto steps = test::runCommand(kFlatsat + " validate default --set duration_orbits=null --set duration_s=3e8");
  INFO(steps.output);
  CHECK(steps.exit_code == 2);
  CHECK(steps.output.find("--set duration_s=3e8: duration_s: 3e+09 steps of 0.1 s: more than a run steps (1e9)") !=
        std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("validate takes --set as run does, a problem of a --set is told at the --set, and a run refused "
          "for one leaves no folder",
          "[system][tools]") {
  const std::string scenario = std::string(FLATSAT_SCENARIO_DIR) + "/default.yaml";
  const auto ok = test::runCommand(kFlatsat + " validate " + scenario +
                                   " --set duration_orbits=null --set duration_s=10");
  INFO(ok.output);
  CHECK(ok.exit_code == 0);
  CHECK(ok.output.find(": ok (") != std::string::npos);
  const auto bad = test::runCommand(kFlatsat + " validate " + scenario + " --set components.gyro.noise_typo=1");
  INFO(bad.output);
  CHECK(bad.exit_code == 2);
  CHECK(bad.output.find("--set components.gyro.noise_typo=1: components.gyro.noise_typo: unknown key") !=
        std::string::npos);
  CHECK(bad.output.find("/tmp/flatsat-check-") == std::string::npos);  // not the resolved copy's place
  const std::string run = test::freshDir("refused-run");
  const auto refused = test::runCommand(test::runLine(scenario, run, "--set components.gyro.noise_typo=1"));
  INFO(refused.output);
  CHECK(refused.exit_code == 2);
  CHECK(refused.output.find("--set components.gyro.noise_typo=1:") != std::string::npos);
  CHECK_FALSE(fs::exists(run));
}

TEST_CASE("orbit prints a column header, Vallado's rows, and says why it exits 1", "[system][tools]") {
  const std::string tle = std::string(FLATSAT_SOURCE_DIR) + "/data/sgp4/SGP4-VER.TLE";
  const auto rows = tool("orbit --tle " + tle + " --no-checksum --from 0 --to 360 --step 360");
  INFO(rows.output);
  CHECK(rows.exit_code == 1);  // the file's deliberately failing sets
  const auto out = lines(rows.output);
  REQUIRE(out.size() > 3);
  CHECK(out[0] == "# t [min after epoch], r x y z [km], v x y z [km/s]: SGP4, TEME frame");
  CHECK(out[1] == "5 xx");
  // data/sgp4/tcppver.out (Vallado et al. 2006), satellite 5 at 0 and 360 min: the same digits.
  const std::string published = readFile(std::string(FLATSAT_SOURCE_DIR) + "/data/sgp4/tcppver.out");
  CHECK(published.find(out[2]) != std::string::npos);
  CHECK(published.find(out[3]) != std::string::npos);
  const auto said = test::runCommand("(" + kFlatsat + " orbit --tle " + tle + " --no-checksum 2>&1 >/dev/null)");
  // Over a day at 120 min steps, five of the file's sets end at an SGP4 error, as Vallado et al. (2006) list them: 22312, 28872, 29141, 33333, 33334.
  CHECK(said.output.find("flatsat orbit: 5 of 33 element sets stopped early at an SGP4 error (above); exit status 1") !=
        std::string::npos);
}

TEST_CASE("topics lists the live topics with their producers and rates", "[system][tools]") {
  BackgroundRig rig("topics");
  const auto result = tool("topics --seconds 3 --json");
  INFO(result.output);
  REQUIRE(result.exit_code == 0);
  const auto out = nlohmann::json::parse(result.output);
  std::map<std::string, nlohmann::json> topics;
  for (const auto& t : out["topics"]) topics[t["name"].get<std::string>()] = t;

  REQUIRE(topics.count("flatsat/truth") == 1);
  const auto& truth = topics["flatsat/truth"];
  CHECK(truth["type"] == "flatsat::msg::TruthState");
  REQUIRE(truth["producers"].size() == 1);
  CHECK(truth["producers"][0]["name"] == "dynamics_server");
  CHECK(truth["rate_hz"].get<double>() == Approx(10.0).margin(3.0));  // paced, step 0.1 s
  CHECK(topics["flatsat/gyro"]["producers"][0]["name"] == "gyro");
  std::set<std::string> health_producers;
  for (const auto& p : topics["flatsat/health"]["producers"]) health_producers.insert(p["name"]);
  CHECK(health_producers == std::set<std::string>(kComponents.begin(), kComponents.end()));

  const auto table = tool("topics --seconds 2");
  INFO(table.output);
  CHECK(table.exit_code == 0);
  bool truth_line = false;
  for (const auto& line : lines(table.output)) {
    truth_line |= line.rfind("flatsat/truth ", 0) == 0 && line.find("TruthState") != std::string::npos &&
                  line.find("dynamics_server") != std::string::npos;
  }
  CHECK(truth_line);

  // Live topics only, unless --all: the default rig has no star tracker.
  CHECK(topics.count("flatsat/star_tracker") == 0);
  for (const auto& [name, t] : topics) CHECK_FALSE(t["producers"].empty());
  const auto all = tool("topics --seconds 1 --all --json");
  INFO(all.output);
  REQUIRE(all.exit_code == 0);
  bool star_tracker = false;
  const auto every = nlohmann::json::parse(all.output);
  for (const auto& t : every["topics"]) star_tracker |= t["name"] == "flatsat/star_tracker";
  CHECK(star_tracker);

  // One topic, as ros2 topic info -v: type, QoS, producers and consumers.
  const auto info = tool("topics info gyro --json");
  INFO(info.output);
  REQUIRE(info.exit_code == 0);
  const auto gyro = nlohmann::json::parse(info.output);
  CHECK(gyro["type"] == "flatsat::msg::GyroReading");
  CHECK(gyro["qos_preset"] == "stepped");
  CHECK(gyro["writer_qos"]["reliability"] == "reliable");
  CHECK(gyro["writer_qos"]["ownership"] == "exclusive");
  REQUIRE(gyro["producers"].size() == 1);
  CHECK(gyro["producers"][0]["participant"] == "gyro");
  std::set<std::string> consumers;
  for (const auto& c : gyro["consumers"]) consumers.insert(c["participant"].get<std::string>());
  CHECK(consumers.count("estimator") == 1);
  CHECK(consumers.count("recorder") == 1);
  const auto info_table = tool("topics info flatsat/gyro");
  INFO(info_table.output);
  CHECK(info_table.exit_code == 0);
  CHECK(info_table.output.find("producers (1):") != std::string::npos);
}

TEST_CASE("types lists the topic types and prints one's IDL", "[system][tools]") {
  const auto list = test::runCommand(kFlatsat + " types");
  INFO(list.output);
  REQUIRE(list.exit_code == 0);
  bool truth_row = false;
  for (const auto& line : lines(list.output)) {
    truth_row |= line.rfind("flatsat::msg::TruthState ", 0) == 0 && line.find("flatsat/truth") != std::string::npos;
  }
  CHECK(truth_row);
  const auto by_topic = test::runCommand(kFlatsat + " types truth");
  INFO(by_topic.output);
  REQUIRE(by_topic.exit_code == 0);
  CHECK(by_topic.output.find("struct TruthState") != std::string::npos);
  CHECK(by_topic.output.find("q_inertial_body") != std::string::npos);
  CHECK(by_topic.output.find("struct SampleHeader") != std::string::npos);  // includes inlined
  CHECK(test::runCommand(kFlatsat + " types TruthState").output == by_topic.output);
  const auto unknown = test::runCommand(kFlatsat + " types NoSuchType");
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.output.find("no type or topic 'NoSuchType'") != std::string::npos);
}

TEST_CASE("echo prints a topic's samples as lines or as JSON", "[system][tools]") {
  BackgroundRig rig("echo");
  const auto json = tool("echo flatsat/truth --json --count 3 --timeout 30");
  INFO(json.output);
  REQUIRE(json.exit_code == 0);
  const auto docs = parseDocuments(json.output);
  REQUIRE(docs.size() == 3);
  for (std::size_t i = 0; i < docs.size(); ++i) {
    CHECK(docs[i]["header"]["source"] == "dynamics_server");
    CHECK(docs[i]["q_inertial_body"].size() == 4);
    if (i > 0) CHECK(docs[i]["header"]["step"] > docs[i - 1]["header"]["step"]);
  }

  const auto text = tool("echo gyro --count 2 --timeout 30");
  INFO(text.output);
  CHECK(text.exit_code == 0);
  const auto gyro_lines = lines(text.output);
  REQUIRE(gyro_lines.size() == 2);
  for (const auto& line : gyro_lines) {
    CHECK(line.find("header.source=\"gyro\"") != std::string::npos);
    CHECK(line.find("w_body_rad_s=[") != std::string::npos);
  }

  const auto health = tool("echo health --json --count 1 --timeout 30");
  INFO(health.output);
  CHECK(health.exit_code == 0);
  CHECK(parseDocuments(health.output).at(0)["state"].is_string());  // enums by name

  const auto unknown = test::runCommand(kFlatsat + " echo flatsat/no_such_topic --count 1");
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.output.find("unknown topic") != std::string::npos);

  // One compact document per line, as jq and scripts take them.
  const auto jsonl = tool("echo truth --jsonl --count 3 --timeout 30");
  INFO(jsonl.output);
  CHECK(jsonl.exit_code == 0);
  const auto truth_lines = lines(jsonl.output);
  REQUIRE(truth_lines.size() == 3);
  for (const auto& line : truth_lines) CHECK(nlohmann::json::parse(line)["header"]["source"] == "dynamics_server");

  // --field: a leaf, as text and as JSON.
  const auto steps = tool("echo gyro --field header.step --count 3 --timeout 30");
  INFO(steps.output);
  CHECK(steps.exit_code == 0);
  std::vector<long> step_values;
  for (const auto& line : lines(steps.output)) {
    long step = -1;
    CHECK(std::sscanf(line.c_str(), "header.step=%ld", &step) == 1);
    step_values.push_back(step);
  }
  REQUIRE(step_values.size() == 3);
  CHECK(step_values[1] > step_values[0]);
  CHECK(step_values[2] > step_values[1]);
  const auto rate_z = tool("echo gyro --field w_body_rad_s[2] --jsonl --count 2 --timeout 30");
  INFO(rate_z.output);
  CHECK(rate_z.exit_code == 0);
  for (const auto& line : lines(rate_z.output)) CHECK(nlohmann::json::parse(line).is_number());
  const auto no_field = test::runCommand(kFlatsat + " echo gyro --field w_body --count 1");
  INFO(no_field.output);
  CHECK(no_field.exit_code == 2);
  CHECK(no_field.output.find("has no field 'w_body'") != std::string::npos);
  CHECK(no_field.output.find("w_body_rad_s[2]") != std::string::npos);
}

TEST_CASE("hz measures a topic's rate in wall time", "[system][tools]") {
  BackgroundRig rig("hz");
  const auto truth = tool("hz truth --seconds 4 --json");
  INFO(truth.output);
  REQUIRE(truth.exit_code == 0);
  const auto t = nlohmann::json::parse(truth.output);
  CHECK(t["rate_hz"].get<double>() == Approx(10.0).margin(2.5));  // step_s 0.1, paced
  CHECK(t["samples"].get<int>() >= 20);
  CHECK(t["interval_s"]["min"].get<double>() <= t["interval_s"]["mean"].get<double>());
  CHECK(t["interval_s"]["mean"].get<double>() <= t["interval_s"]["max"].get<double>());
  CHECK(t["interval_s"]["std"].get<double>() >= 0.0);

  const auto dipole = tool("hz dipole_cmd --seconds 5");  // unloading: rate_divider 10
  INFO(dipole.output);
  REQUIRE(dipole.exit_code == 0);
  double rate = 0;
  int readouts = 0;
  for (const auto& line : lines(dipole.output)) {
    double rolling = 0;
    if (std::sscanf(line.c_str(), "flatsat/dipole_cmd: rate %lf Hz", &rolling) == 1) {
      ++readouts;  // every second, as ros2 topic hz
      CHECK(rolling == Approx(1.0).margin(0.5));
    }
    std::sscanf(line.c_str(), "flatsat/dipole_cmd: average rate %lf Hz", &rate);
  }
  CHECK(readouts >= 2);
  CHECK(rate == Approx(1.0).margin(0.4));
  CHECK(dipole.output.find("interval [s]: mean") != std::string::npos);
}

TEST_CASE("health --once lists every component of the running rig", "[system][tools]") {
  BackgroundRig rig("health");
  const auto table = tool("health --once");
  INFO(table.output);
  REQUIRE(table.exit_code == 0);
  for (const auto& name : kComponents) {
    CAPTURE(name);
    bool listed = false;
    for (const auto& line : lines(table.output)) {
      listed |= line.rfind(name + " ", 0) == 0 && line.find("RUNNING") != std::string::npos;
    }
    CHECK(listed);
  }
  const auto json = tool("health --once --json");
  INFO(json.output);
  REQUIRE(json.exit_code == 0);
  const auto rows = nlohmann::json::parse(json.output);
  CHECK(rows.size() == kComponents.size());

  // Watching, the first table is the whole rig, never what discovery found so far.
  const auto watch = test::runCommand("timeout -s INT 9 " + kFlatsat + " health --json --every 1 2>/dev/null");
  INFO(watch.output);
  const auto refreshes = lines(watch.output);
  REQUIRE_FALSE(refreshes.empty());
  CHECK(nlohmann::json::parse(refreshes.front()).size() == kComponents.size());
  for (const auto& row : rows) {
    CAPTURE(row.dump());
    CHECK(row["alive"] == true);
    // Granted but not yet handled, as the component saw it: the time master grants, so it has none.
    if (row["component"] == "dynamics_server") CHECK(row["lag_steps"] == 0);
    // A stepping component reports every second; the time master on change only.
    if (row["component"] != "dynamics_server") CHECK(row["age_s"].get<double>() < 5.0);
  }
}

TEST_CASE("param lists, gets and sets the parameters components let an operator set", "[system][tools]") {
  BackgroundRig rig("param");
  const auto listed = tool("param list --json");
  INFO(listed.output);
  REQUIRE(listed.exit_code == 0);
  const auto all = nlohmann::json::parse(listed.output);
  // deploy/scenarios/default.yaml: components.attitude_controller.kp_Nm_per_rad: 1.2, kd 60,
  // components.unloading_controller.gain_per_s: 0.002.
  CHECK(all["attitude_controller"]["values"]["kp_Nm_per_rad"] == 1.2);
  CHECK(all["attitude_controller"]["values"]["kd_Nm_s_per_rad"] == 60.0);
  CHECK(all["unloading_controller"]["values"]["gain_per_s"] == 0.002);
  const auto table = tool("param list attitude_controller");
  INFO(table.output);
  CHECK(table.output.find("attitude_controller    kp_Nm_per_rad                     1.2") != std::string::npos);

  // With its standard error: a missing acknowledgement says why (it failed once in a suite, silently).
  const auto set = test::runCommand(kFlatsat + " param set attitude_controller kp_Nm_per_rad 0.9");
  INFO(set.output);
  CHECK(set.exit_code == 0);
  CHECK(set.output.find("accepted by attitude_controller") != std::string::npos);
  const auto got = tool("param get attitude_controller kp_Nm_per_rad");
  INFO(got.output);
  CHECK(got.exit_code == 0);
  CHECK(got.output == "0.90000000000000002\n");  // 0.9 to 17 digits: the double itself
  const auto refused = tool("param set attitude_controller kp_Nm_per_rad -1");
  INFO(refused.output);
  CHECK(refused.exit_code == 3);
  CHECK(tool("param get attitude_controller kp_Nm_per_rad").output == got.output);  // unchanged
  const auto typo = test::runCommand(kFlatsat + " param get attitude_controller kp_Nm_per_rd");
  INFO(typo.output);
  CHECK(typo.exit_code == 2);
  CHECK(typo.output.find("no settable parameter 'kp_Nm_per_rd' (did you mean 'kp_Nm_per_rad'?)") !=
        std::string::npos);
  const auto nobody = test::runCommand(kFlatsat + " param get estimator gain");
  INFO(nobody.output);
  CHECK(nobody.exit_code == 1);
  CHECK(nobody.output.find("no component 'estimator' announced settable parameters") != std::string::npos);
}

TEST_CASE("export writes one CSV per recorded topic: a row per step, units in the header",
          "[system][tools]") {
  const std::string run = finishedRun("export");
  const std::string recording = run + "/recording.sqlite";
  const auto csv = tool("export " + recording + " --csv --out " + run + "/csv");
  INFO(csv.output);
  REQUIRE(csv.exit_code == 0);
  struct Expected {
    std::string file;
    std::size_t rows;
    std::string column;
  };
  const Expected expected[] = {
      {"truth.csv", 601, "b_body_T[0] [T]"},
      {"magnetometer.csv", 601, "b_body_T[2] [T]"},
      {"sun_sensor.csv", 601, "sun_body_unit[0] [-]"},
      {"gyro.csv", 601, "w_body_rad_s[1] [rad/s]"},
      {"wheel_tach.csv", 601, "wheel_speed_rad_s[3] [rad/s]"},
      {"attitude_estimate.csv", 601, "q_inertial_body[0] [-]"},
      {"wheel_torque_cmd.csv", 601, "torque_Nm[0] [N m]"},
      {"dipole_cmd.csv", 61, "m_body_Am2[0] [A m^2]"},  // rate_divider 10
  };
  for (const auto& e : expected) {
    CAPTURE(e.file);
    const auto rows = lines(readFile(fs::path(run) / "csv" / e.file));
    REQUIRE(rows.size() == e.rows + 1);
    CHECK(rows[0].rfind("header.step [-],header.sim_time_ns [ns],", 0) == 0);
    CHECK(rows[0].find(e.column) != std::string::npos);
    CHECK(rows[1].rfind("0,0,", 0) == 0);  // step 0 at t = 0
  }
  CHECK(fs::exists(fs::path(run) / "csv" / "health.csv"));

  const auto json = tool("export " + recording + " --json --topic truth --out " + run + "/json");
  INFO(json.output);
  REQUIRE(json.exit_code == 0);
  const auto samples = lines(readFile(fs::path(run) / "json" / "truth.jsonl"));
  REQUIRE(samples.size() == 601);
  CHECK(nlohmann::json::parse(samples.back())["header"]["step"] == 600);
  CHECK_FALSE(fs::exists(fs::path(run) / "json" / "gyro.jsonl"));

  CHECK(test::runCommand(kFlatsat + " export " + recording).exit_code == 2);  // neither --csv nor --json

  // info tells what the file holds, as SQLite itself reads it (Debian's sqlite3) and as
  // the run's summary gave it.
  const auto described = tool("info " + recording + " --json");
  INFO(described.output);
  REQUIRE(described.exit_code == 0);
  const auto info = nlohmann::json::parse(described.output);
  CHECK(info["recording_sha256"] == test::readSummary(run)["recording_sha256"]);
  CHECK(info["scenario"] == "default");
  CHECK(info["mode"] == "lockstep");
  std::uint64_t on_disk = fs::file_size(recording);
  if (fs::exists(recording + "-wal")) on_disk += fs::file_size(recording + "-wal");
  CHECK(info["size_bytes"] == on_disk);
  const auto counted = test::runCommand("sqlite3 -readonly " + recording +
                                        " 'SELECT topic, COUNT(*), MIN(sim_time_ns), MAX(sim_time_ns) FROM samples GROUP BY topic'");
  REQUIRE(counted.exit_code == 0);
  std::map<std::string, std::uint64_t> by_sqlite;
  long long first_ns = LLONG_MAX, last_ns = LLONG_MIN;
  for (const auto& row : lines(counted.output)) {
    const auto a = row.find('|'), b = row.find('|', a + 1), c = row.find('|', b + 1);
    by_sqlite[row.substr(0, a)] = std::stoull(row.substr(a + 1, b - a - 1));
    first_ns = std::min(first_ns, std::stoll(row.substr(b + 1, c - b - 1)));
    last_ns = std::max(last_ns, std::stoll(row.substr(c + 1)));
  }
  REQUIRE(info["topics"].size() == by_sqlite.size());
  const double span_s = static_cast<double>(last_ns - first_ns) * 1e-9;
  CHECK(span_s == Approx(60.0));  // the run's 60 s
  CHECK(info["duration_sim_s"].get<double>() == Approx(span_s).margin(1e-9));
  CHECK(info["first_step"] == 0);
  CHECK(info["last_step"] == 600);
  for (const auto& t : info["topics"]) {
    CAPTURE(t.dump());
    CHECK(t["count"] == by_sqlite.at(t["name"]));
    CHECK(t["rate_hz"].get<double>() == Approx(static_cast<double>(by_sqlite.at(t["name"])) / span_s));
  }
  CHECK(info["topics"][11]["name"] == "flatsat/truth");
  CHECK(info["topics"][11]["type"] == "flatsat::msg::TruthState");
  CHECK(info["duration_wall_s"].get<double>() > 0.0);
  const auto table = tool("info " + recording);
  CHECK(table.output.find("Digest:        " + info["recording_sha256"].get<std::string>()) != std::string::npos);
  // The recorder kept the same digest as it stored the samples; one sample changed after the run shows.
  CHECK(info["recorder_sha256"] == info["recording_sha256"]);
  REQUIRE(test::runCommand("sqlite3 " + recording +
                           " \"UPDATE samples SET payload = zeroblob(length(payload)) WHERE rowid = "
                           "(SELECT MIN(rowid) FROM samples WHERE topic = 'flatsat/gyro')\"")
              .exit_code == 0);
  const auto tampered = tool("info " + recording);
  CHECK(tampered.exit_code == 1);
  CHECK(tampered.output.find("NOT the recorder's " + info["recording_sha256"].get<std::string>()) !=
        std::string::npos);
  CHECK(tool("info " + run + "/nothing.sqlite").exit_code == 1);
  fs::remove_all(run);
}

TEST_CASE("plot draws the review figures of a recording as PNG", "[system][tools]") {
  const std::string run = finishedRun("plot");
  const auto result = tool("plot " + run + "/recording.sqlite --out " + run + "/plots");
  INFO(result.output);
  REQUIRE(result.exit_code == 0);
  for (const std::string name : {"pointing_error", "body_rates", "wheels", "dipole", "field",
                                 "estimator_error", "ground_track"}) {
    CAPTURE(name);
    const fs::path png = fs::path(run) / "plots" / (name + ".png");
    REQUIRE(fs::exists(png));
    CHECK(fs::file_size(png) > 10000);  // a drawn figure, not an empty canvas
    CHECK(readFile(png).rfind("\x89PNG\r\n\x1a\n", 0) == 0);
    CHECK(result.output.find(png.string()) != std::string::npos);
  }
  CHECK(fs::exists(fs::path(run) / "plots" / "gnuplot" / "plots.gp"));
  fs::remove_all(run);
}

TEST_CASE("clean-shm removes the Fast DDS files no process uses, and only those", "[system][tools]") {
  const std::string tag = "flatsat_test_" + std::to_string(::getpid());
  const fs::path shm = "/dev/shm";
  // What a SIGKILLed participant leaves: a transport segment and its port's
  // named mutex (the shared-memory acknowledgements of a lockstep rig).
  const fs::path stale_segment = shm / ("fastrtps_" + tag);
  const fs::path stale_mutex = shm / ("sem.fastrtps_" + tag + "_mutex");
  const fs::path in_use = shm / ("sem.fastrtps_" + tag + "_open");  // this process holds it open
  const fs::path foreign = shm / ("not_fastdds_" + tag);
  // An hour old: the tool runs with a grace that keeps the fresh segments of
  // the tests running alongside this one.
  const auto an_hour_ago = fs::file_time_type::clock::now() - std::chrono::hours(1);
  for (const auto& path : {stale_segment, stale_mutex, in_use, foreign}) {
    std::ofstream(path) << "x";
    fs::last_write_time(path, an_hour_ago);
  }
  {
    std::ifstream held(in_use);
    const auto result = test::runCommand(kFlatsat + " clean-shm --min-age-s 600");
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    CHECK(!fs::exists(stale_segment));
    CHECK(!fs::exists(stale_mutex));
    CHECK(fs::exists(in_use));
    CHECK(fs::exists(foreign));
  }
  for (const auto& path : {stale_segment, stale_mutex, in_use, foreign}) fs::remove(path);
}
