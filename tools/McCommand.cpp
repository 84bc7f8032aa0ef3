// SPDX-License-Identifier: Apache-2.0
#include "tools/McCommand.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bus/Scenario.hpp"
#include "bus/Shutdown.hpp"
#include "components/Registry.hpp"
#include "rig/ComposedRun.hpp"
#include "analysis/McTable.hpp"
#include "rig/RunDirectory.hpp"
#include "rig/Spawn.hpp"

namespace flatsat::tools {

using rig::composedProblems;
using rig::recordOnceASecond;
using rig::defaultRunDirectory;
using rig::spawnLogged;
using rig::writeRunScenario;
using analysis::McRun;
using analysis::mcCsv;
using analysis::mcNumericKeys;
using analysis::mcSummary;
using analysis::mcTable;

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct McOptions {
  std::string scenario;
  std::string out;
  std::vector<std::string> overrides;
  int runs = 0;
  int jobs = 1;
  std::optional<std::uint64_t> seed0;
};

/// Whether the campaign sets the recorder's decimation itself.
bool setsRecordingDecimation(const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) {
    if (o.rfind("components.recorder.record_every_steps", 0) == 0) return true;
  }
  return false;
}

/// The scenario with the campaign's overrides (and the recording decimation
/// it adds to them), checked as `flatsat run` checks it, resolved into
/// DIR/scenario.yaml; empty problems when it can run composed.
std::vector<std::string> checkCampaign(McOptions& o, bus::Scenario& scenario) {
  if (o.runs < 1) return {"--runs " + std::to_string(o.runs) + ": must be >= 1"};
  if (o.jobs < 1) return {"--jobs " + std::to_string(o.jobs) + ": must be >= 1"};
  if (!fs::is_regular_file(o.scenario)) return {o.scenario + ": no such scenario file"};
  if (fs::exists(o.out) && !fs::is_empty(o.out)) {
    return {"--out " + o.out + ": exists and is not empty; choose another directory"};
  }
  try {
    scenario = bus::loadScenario(writeRunScenario(o.scenario, o.out, o.overrides));
    // A campaign's runs record one step a second unless it says otherwise:
    // its table comes from the summaries, and inserting every sample of every
    // run was most of a run's cost (a one-orbit default run: 7.1 s at every
    // step, 1.8 s at 1 Hz).
    if (!setsRecordingDecimation(o.overrides)) {
      o.overrides.push_back(recordOnceASecond(scenario.step_s));
      scenario = bus::loadScenario(writeRunScenario(o.scenario, o.out, o.overrides));
    }
  } catch (const std::exception& e) {
    return {e.what()};
  }
  auto problems = checkScenario(scenario, o.out);
  for (const auto& p : composedProblems(scenario)) problems.push_back("cannot run composed: " + p);
  for (auto& p : problems) p = o.scenario + ": " + p;
  return problems;
}

/// Starts run `index`: this executable's `run` with its stdout and stderr to `log`;
/// throws std::runtime_error when it cannot.
pid_t startRun(const McOptions& o, const std::string& run_dir, std::uint64_t seed, const std::string& log) {
  const std::string exe = fs::canonical("/proc/self/exe").string();
  std::vector<std::string> args{exe,          "run",  fs::absolute(o.scenario).string(), "--composed",
                                "--seed",     std::to_string(seed), "--no-plots", "-q",
                                "--out",      run_dir};
  for (const auto& assignment : o.overrides) {
    args.push_back("--set");
    args.push_back(assignment);
  }
  return spawnLogged(args, log);
}

void showProgress(int done, int failed, int total, Clock::time_point start, bool last) {
  static const bool terminal = ::isatty(STDERR_FILENO) == 1;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  const double eta = done > 0 ? elapsed / done * (total - done) : 0.0;
  std::fprintf(stderr, "%smc: %d/%d runs done, %d failed, elapsed %.1f s, eta %.1f s%s",
               terminal ? "\r" : "", done, total, failed, elapsed, eta, (last || !terminal) ? "\n" : "   ");
}

int runCampaign(McOptions o) {
  bus::Scenario scenario;
  if (o.out.empty()) {
    try {
      o.out = defaultRunDirectory(bus::loadScenario(o.scenario).name + "-mc");
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 2;
    }
  }
  const bool new_out = !fs::exists(o.out);
  if (const auto problems = checkCampaign(o, scenario); !problems.empty()) {
    for (const auto& p : problems) std::cerr << "error: mc: " << p << "\n";
    if (new_out) fs::remove_all(o.out);
    return 2;
  }
  const std::uint64_t seed0 = o.seed0.value_or(scenario.seed);
  std::cerr << "mc: " << o.runs << " composed runs of '" << scenario.name << "', seeds " << seed0 << ".."
            << seed0 + static_cast<std::uint64_t>(o.runs - 1) << ", " << o.jobs << " at a time, into " << o.out
            << "\n";

  std::vector<McRun> runs(static_cast<std::size_t>(o.runs));
  std::map<pid_t, int> running;  // pid -> run index
  int next = 0, done = 0, failed = 0;
  bool stopping = false;
  const auto start = Clock::now();
  while (done < next || (next < o.runs && !stopping)) {
    while (!stopping && next < o.runs && static_cast<int>(running.size()) < o.jobs) {
      McRun& run = runs[static_cast<std::size_t>(next)];
      run.index = next;
      run.seed = seed0 + static_cast<std::uint64_t>(next);
      run.log = (fs::path(o.out) / ("run-" + std::to_string(next) + ".log")).string();
      pid_t pid = -1;
      try {
        pid = startRun(o, (fs::path(o.out) / ("run-" + std::to_string(next))).string(), run.seed, run.log);
      } catch (const std::runtime_error& e) {
        std::cerr << "error: mc: run " << next << ": " << e.what() << "\n";
        stopping = true;
        break;
      }
      running[pid] = next++;
    }
    if (running.empty()) break;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno != EINTR) break;
      if (bus::shutdownRequested() && !stopping) {
        // Runs under way are told to stop; no new ones start.
        stopping = true;
        for (const auto& [child, index] : running) ::kill(child, SIGTERM);
      }
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    McRun& run = runs[static_cast<std::size_t>(it->second)];
    running.erase(it);
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    const fs::path summary_file = fs::path(o.out) / ("run-" + std::to_string(run.index)) / "summary.json";
    if (run.exit_code == 0 && fs::exists(summary_file)) {
      std::ifstream(summary_file) >> run.summary;
      fs::remove(run.log);  // the run directory holds its own logs
      run.log.clear();
    } else {
      ++failed;
      std::cerr << (::isatty(STDERR_FILENO) ? "\n" : "") << "mc: run " << run.index << " (seed " << run.seed
                << ") failed with exit status " << run.exit_code << "; log " << run.log << "\n";
    }
    ++done;
    showProgress(done, failed, o.runs, start, done == o.runs);
  }
  runs.resize(static_cast<std::size_t>(next));  // an interrupted campaign reports the runs it started

  const auto keys = mcNumericKeys(runs);
  const auto summary = mcSummary(o.scenario, runs, keys);
  std::ofstream(fs::path(o.out) / "mc.csv") << mcCsv(runs, keys);
  std::ofstream(fs::path(o.out) / "mc_summary.json") << summary.dump(2) << "\n";
  std::cout << "mc: " << summary["succeeded"] << " of " << o.runs << " runs succeeded ("
            << (fs::path(o.out) / "mc.csv").string() << ", " << (fs::path(o.out) / "mc_summary.json").string()
            << ")\n"
            << mcTable(summary);
  return failed == 0 && next == o.runs ? 0 : 1;
}

}  // namespace

CLI::App* addMcCommand(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<McOptions>();
  auto* mc = app.add_subcommand("mc", "Monte Carlo: seeded composed runs in parallel, one table");
  mc->add_option("scenario", o->scenario, "scenario file (YAML)")->required();
  mc->add_option("--runs", o->runs, "number of runs")->required();
  mc->add_option("--jobs", o->jobs, "runs at a time")->capture_default_str();
  mc->add_option("--out", o->out, "campaign directory (default runs/<name>-mc-<time>)");
  mc->add_option("--seed0", o->seed0, "seed of run 0; run i has seed0 + i (default: the scenario's seed)");
  mc->add_option("--set", o->overrides, "override a scenario key in every run: key.path=value");
  mc->callback([o, &exit_code] { exit_code = runCampaign(*o); });
  return mc;
}

}  // namespace flatsat::tools
