// SPDX-License-Identifier: Apache-2.0
// Recordings survive crashes: SIGKILL the recorder (and, in a second run,
// the dynamics server) in the middle of a lockstep run. The recording still
// opens and exports; every step up to the last committed one is complete and
// each of its samples is byte-identical to the same sample of an
// uninterrupted run of the scenario. `flatsat run --resume` then completes
// it into exactly the uninterrupted run's recording. The recording is read
// here with SQLite directly, not through the project's Recording class.
#include <signal.h>
#include <sqlite3.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>
#include <tuple>

#include <catch2/catch.hpp>

#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"
#include "tests/support/TestDomain.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

using test::kDefault;
const std::string kArgs = "--set duration_orbits=null --set duration_s=300";
constexpr std::uint64_t kCommitEvery = 50;  // recorder's default commit_every_steps
constexpr std::uint64_t kKillAfter = 150;   // committed truth samples seen before the kill

/// (topic, source, step) -> payload, for every stepped sample (health and the
/// as-they-come topics carry wall-clock data and are left out).
using Samples = std::map<std::tuple<std::string, std::string, std::uint64_t>, std::string>;

Samples readSamples(const std::string& path) {
  sqlite3* db = nullptr;
  Samples samples;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    throw std::runtime_error(path + ": cannot open");
  }
  sqlite3_stmt* stmt = nullptr;
  const char* sql =
      "SELECT topic, source, step, payload FROM samples WHERE topic NOT IN "
      "('flatsat/health', 'flatsat/fault_cmd', 'flatsat/fault_event')";
  if (sqlite3_prepare_v2(db, sql, -1, &stmt, nullptr) == SQLITE_OK) {
    while (sqlite3_step(stmt) == SQLITE_ROW) {
      const auto* blob = static_cast<const char*>(sqlite3_column_blob(stmt, 3));
      samples[{reinterpret_cast<const char*>(sqlite3_column_text(stmt, 0)),
               reinterpret_cast<const char*>(sqlite3_column_text(stmt, 1)),
               static_cast<std::uint64_t>(sqlite3_column_int64(stmt, 2))}] =
          std::string(blob, blob + sqlite3_column_bytes(stmt, 3));
    }
  }
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return samples;
}

/// The default scenario run uninterrupted into `dir` with `args`: its samples.
Samples referenceRun(const std::string& dir, const std::string& args) {
  const auto run = test::runCommand(test::kFlatsat + " run " + kDefault + " --out " + dir + " " + args);
  INFO(run.output);
  REQUIRE(run.exit_code == 0);
  return readSamples(dir + "/recording.sqlite");
}

std::uint64_t truthCount(const Samples& samples) {
  std::uint64_t n = 0;
  for (const auto& [key, payload] : samples) n += std::get<0>(key) == "flatsat/truth";
  return n;
}

/// Samples of `crashed` that the uninterrupted run did not record, or recorded otherwise.
std::uint64_t mismatchedSamples(const Samples& crashed, const Samples& reference) {
  std::uint64_t mismatched = 0;
  for (const auto& [key, payload] : crashed) {
    const auto it = reference.find(key);
    if (it == reference.end() || it->second != payload) ++mismatched;
  }
  return mismatched;
}

/// The pid of `executable` started for the run into `out` (its --out argument).
pid_t findProcess(const std::string& executable, const std::string& out) {
  for (const auto& entry : fs::directory_iterator("/proc")) {
    std::ifstream in(entry.path() / "cmdline", std::ios::binary);
    std::string cmdline((std::istreambuf_iterator<char>(in)), {});
    std::vector<std::string> argv;
    for (std::stringstream ss(cmdline); std::getline(ss, cmdline, '\0');) argv.push_back(cmdline);
    if (argv.empty() || fs::path(argv[0]).filename() != executable) continue;
    for (std::size_t i = 0; i + 1 < argv.size(); ++i) {
      if (argv[i] == "--out" && argv[i + 1] == out) return std::stoi(entry.path().filename());
    }
  }
  return -1;
}

std::string readFile(const std::string& path) {
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("SIGKILL of the recorder or the dynamics server leaves a readable recording, and --resume completes it",
          "[recorder][system][crash]") {
  test::exportTestDomain();
  const std::string reference_dir = test::freshDir("crash-reference");
  const Samples reference = referenceRun(reference_dir, "-q --no-plots " + kArgs);
  const std::uint64_t reference_steps = truthCount(reference);
  REQUIRE(reference_steps == 3001);

  std::map<std::uint64_t, std::vector<Samples::key_type>> reference_by_step;
  for (const auto& [key, payload] : reference) reference_by_step[std::get<2>(key)].push_back(key);

  for (const std::string victim : {"recorder", "dynamics_server"}) {
    CAPTURE(victim);
    {
      const std::string out = test::freshDir("crash-" + victim);
      const std::string recording = out + "/recording.sqlite";
      const pid_t launcher = test::startCommand(
          test::kFlatsat + " run " + kDefault + " -q --no-plots --out " + out + " " + kArgs, out + ".log");
      // Kill once the recorder has committed a few transactions.
      std::uint64_t seen = 0;
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
      while (seen < kKillAfter && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        if (fs::exists(recording)) seen = truthCount(readSamples(recording));
      }
      const pid_t pid = findProcess("flatsat-" + victim, out);
      if (pid > 0) ::kill(pid, SIGKILL);
      const int exit_code = test::waitCommand(launcher);
      const std::string log = readFile(out + ".log");
      INFO(log);
      REQUIRE(pid > 0);
      REQUIRE(seen >= kKillAfter);
      CHECK(exit_code != 0);
      // The log's end in the expansion: a truncated CI log still shows it.
      CHECK_THAT(log.substr(log.size() > 1500 ? log.size() - 1500 : 0),
                 Catch::Matchers::Contains("'" + victim + "' died (killed by signal 9)"));

      const Samples crashed = readSamples(recording);
      // Complete for `steps` steps: every reference sample of steps 0..steps-1 is there.
      std::uint64_t steps = 0;
      const auto complete = [&](std::uint64_t step) {
        for (const auto& key : reference_by_step[step]) {
          if (crashed.count(key) == 0) return false;
        }
        return true;
      };
      while (steps < reference_steps && complete(steps)) ++steps;
      INFO("seen " << seen << " committed truth samples before the kill; complete for " << steps << " steps");
      CHECK(steps >= seen);  // nothing committed before the kill was lost
      CHECK(steps < reference_steps);
      if (victim == "recorder") {
        // Killed, it commits nothing more: the recording ends at a commit.
        CHECK(steps % kCommitEvery == 0);
        CHECK(truthCount(crashed) == steps);
      }
      // Whatever was recorded is exactly what the uninterrupted run recorded.
      CHECK(mismatchedSamples(crashed, reference) == 0);

      const auto exported = test::runCommand(test::kFlatsat + " export " + recording +
                                             " --csv -t truth -o " + out + "/export");
      INFO(exported.output);
      CHECK(exported.exit_code == 0);
      std::ifstream csv(out + "/export/truth.csv");
      std::uint64_t rows = 0;
      for (std::string line; std::getline(csv, line);) ++rows;
      CHECK(rows == 1 + truthCount(crashed));  // header + one row per truth sample

      // `--resume` goes on from the last complete step and ends with the
      // uninterrupted run's recording, bit for bit (after the recorder's
      // death composed: the rig is the same either way).
      const auto resumed = test::runCommand(test::kFlatsat + " run " + kDefault + " --no-plots --resume " + out +
                                            (victim == "recorder" ? " --composed" : ""));
      INFO(resumed.output);
      REQUIRE(resumed.exit_code == 0);
      CHECK(resumed.output.find("steps 0.." + std::to_string(steps - 1) + " are recorded") != std::string::npos);
      CHECK(test::readSummary(out)["recording_sha256"] == test::readSummary(reference_dir)["recording_sha256"]);
      CHECK(readSamples(recording) == reference);
      CHECK(fs::exists(fs::path(out) / "logs-before-resume"));
      fs::remove_all(out);
      fs::remove(out + ".log");
    }
  }
  fs::remove_all(reference_dir);
}

TEST_CASE("flatsat run --resume refuses, with the reason, what it cannot continue as one run", "[recorder][system][crash]") {
  test::exportTestDomain();
  const std::string out = test::freshDir("resume-refused");
  const auto first = test::runCommand(test::kFlatsat + " run " + kDefault + " --composed -q --no-plots --out " + out +
                                      " --set duration_orbits=null --set duration_s=5");
  REQUIRE(first.exit_code == 0);
  const auto resume = [&](const std::string& extra) {
    return test::runCommand(test::kFlatsat + " run " + kDefault + " -q --no-plots --resume " + out + " " + extra);
  };
  const auto with_set = resume("--set seed=3");
  CHECK(with_set.exit_code == 2);
  CHECK(with_set.output.find("--set, --seed and --external do not apply") != std::string::npos);
  const auto other = test::runCommand(test::kFlatsat + " run " + std::string(FLATSAT_SCENARIO_DIR) +
                                      "/mekf.yaml -q --no-plots --resume " + out);
  CHECK(other.exit_code == 2);
  CHECK(other.output.find("holds a run of 'default', not of 'mekf'") != std::string::npos);

  // An operator command in the recording: given at a wall-clock moment, it cannot be repeated.
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open((out + "/recording.sqlite").c_str(), &db) == SQLITE_OK);
  REQUIRE(sqlite3_exec(db, "INSERT INTO samples VALUES ('flatsat/fault_cmd', 3, 'flatsat-cmd', 0, x'00')", nullptr,
                       nullptr, nullptr) == SQLITE_OK);
  sqlite3_close(db);
  const auto commanded = resume("");
  INFO(commanded.output);
  CHECK(commanded.exit_code == 2);
  CHECK(commanded.output.find("holds 1 operator command(s)") != std::string::npos);
  fs::remove_all(out);
}

TEST_CASE("SIGKILL of a composed run: its readers take the open transaction back, and --resume completes it",
          "[recorder][system][crash][composed]") {
  // A composed rig writes its recording with a rollback journal (bus/Recording.hpp,
  // Journal::kRollback): killed in a transaction, it leaves the journal "hot", which a
  // read-only SQLite connection cannot take back.
  test::exportTestDomain();
  const std::string args =
      "--composed -q --no-plots --set duration_orbits=null --set duration_s=20000 "
      "--set components.recorder.record_every_steps=10";
  const std::string reference_dir = test::freshDir("crash-composed-reference");
  const Samples reference = referenceRun(reference_dir, args);
  REQUIRE(truthCount(reference) == 200000 / 10 + 1);  // steps 0..200000 of 0.1 s, every tenth

  // Killed while its journal is there: in a transaction, as nearly always.
  const std::string out = test::freshDir("crash-composed");
  const std::string recording = out + "/recording.sqlite";
  const std::string journal = recording + "-journal";
  bool hot = false;
  for (int attempt = 0; attempt < 3 && !hot; ++attempt) {
    fs::remove_all(out);
    const pid_t run = test::startCommand(test::kFlatsat + " run " + kDefault + " --out " + out + " " + args,
                                         out + ".log");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    std::error_code error;
    while (std::chrono::steady_clock::now() < deadline &&
           (fs::file_size(recording, error) < 8'000'000 || error || fs::file_size(journal, error) == 0 || error)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ::kill(run, SIGKILL);
    CHECK(test::waitCommand(run) == 128 + SIGKILL);
    hot = fs::exists(journal) && fs::file_size(journal) > 0;
  }
  REQUIRE(hot);

  const auto info = test::runCommand(test::kFlatsat + " info " + recording);
  INFO(info.output);
  CHECK(info.exit_code == 0);
  CHECK(!fs::exists(journal));  // taken back by the reader
  const Samples crashed = readSamples(recording);  // read-only, as any other reader
  const std::uint64_t truths = truthCount(crashed);
  CHECK(truths > 0);
  CHECK(truths < truthCount(reference));
  CHECK(mismatchedSamples(crashed, reference) == 0);
  std::uint64_t last_step = 0;
  for (const auto& [key, payload] : crashed) last_step = std::max(last_step, std::get<2>(key));
  // Commits end at step boundaries: every recorded step is whole.
  std::uint64_t missing = 0;
  for (const auto& [key, payload] : reference) {
    if (std::get<2>(key) <= last_step && crashed.count(key) == 0) ++missing;
  }
  CHECK(missing == 0);

  const auto resumed = test::runCommand(test::kFlatsat + " run " + kDefault + " --no-plots --resume " + out +
                                        " --composed");
  INFO(resumed.output);
  REQUIRE(resumed.exit_code == 0);
  CHECK(test::readSummary(out)["recording_sha256"] == test::readSummary(reference_dir)["recording_sha256"]);
  fs::remove_all(out);
  fs::remove(out + ".log");
  fs::remove_all(reference_dir);
}
