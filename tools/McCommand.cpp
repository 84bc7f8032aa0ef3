// SPDX-License-Identifier: Apache-2.0
#include "tools/ScenarioName.hpp"
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
#include "rig/Campaign.hpp"
#include "rig/RunDirectory.hpp"
#include "tools/McSlurm.hpp"
#include "flatsat_version.hpp"

namespace flatsat::tools {

using rig::composedProblems;
using rig::recordOnceASecond;
using rig::defaultRunDirectory;
using rig::Campaign;
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
  bool runs_given = false;
  int jobs = 1;
  std::optional<std::uint64_t> seed0;
  bool use_slurm = false;
  rig::SlurmJobOptions slurm;
  bool no_wait = false;
  std::string collect;  ///< --collect DIR
  std::string resume;   ///< --resume DIR
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

void showProgress(int done, int failed, int total, Clock::time_point start, bool last) {
  static const bool terminal = ::isatty(STDERR_FILENO) == 1;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  const double eta = done > 0 ? elapsed / done * (total - done) : 0.0;
  std::fprintf(stderr, "%smc: %d/%d runs done, %d failed, elapsed %.1f s, eta %.1f s%s",
               terminal ? "\r" : "", done, total, failed, elapsed, eta, (last || !terminal) ? "\n" : "   ");
}

/// Runs `indices` of the campaign on this host, J at a time; false when interrupted.
bool runHere(const Campaign& c, const std::vector<int>& indices, int jobs) {
  std::cerr << "mc: " << indices.size() << " composed runs of '" << c.name << "', " << jobs
            << " at a time, into " << c.dir << "\n";
  const auto start = Clock::now();
  std::vector<rig::StartedRun> running;
  std::size_t next = 0;
  int done = 0, failed = 0;
  bool stopping = false;
  const int total = static_cast<int>(indices.size());
  while (!running.empty() || (next < indices.size() && !stopping)) {
    // Every pass, not only when a wait is interrupted: a Ctrl-C that lands
    // while a run is being started must not let further runs start.
    if (bus::shutdownRequested() && !stopping) {
      stopping = true;
      for (const auto& run : running) ::kill(run.pid, SIGTERM);
    }
    while (!stopping && next < indices.size() && static_cast<int>(running.size()) < jobs) {
      const int index = indices[next];
      rig::clearRun(c, index);
      try {
        running.push_back(rig::startRun(c, index));
      } catch (const std::runtime_error& e) {
        std::cerr << "error: mc: run " << index << ": " << e.what() << "\n";
        stopping = true;
        break;
      }
      ++next;
    }
    if (running.empty()) break;
    const auto ended = rig::waitForRun(c, running);
    if (!ended) continue;  // interrupted: the next pass looks at why
    const auto& [index, status] = *ended;
    if (!status.unrecorded.empty()) {
      std::cerr << "error: mc: run " << index << ": its end is not recorded: " << status.unrecorded << "\n";
    }
    if (status.exit_code != 0 || !status.unrecorded.empty()) {
      ++failed;
      std::cerr << (::isatty(STDERR_FILENO) ? "\n" : "") << "mc: run " << index << " (seed " << rig::runSeed(c, index)
                << ") failed with exit status " << status.exit_code << "; log " << rig::runLog(c, index) << "\n";
    }
    ++done;
    showProgress(done, failed, total, start, done == total);
  }
  int local_runners = 1;
  while (fs::exists(fs::path(c.dir) / "cost" / ("local-" + std::to_string(local_runners) + ".json"))) {
    ++local_runners;
  }
  rig::writeRunnerCost(c, "local-" + std::to_string(local_runners),
                       std::chrono::duration<double>(Clock::now() - start).count());
  return !stopping;
}

/// Gathers every run of the campaign into DIR/mc.csv and DIR/mc_summary.json
/// and prints the table; 0 when every run succeeded, else 1.
int gather(const Campaign& c) {
  std::vector<McRun> runs;
  for (int i = 0; i < c.runs; ++i) runs.push_back(rig::gatherRun(c, i));
  const auto slurm_submissions = submissions(c);
  if (!slurm_submissions.empty()) explainSlurmFailures(c, runs);
  const auto keys = mcNumericKeys(runs);
  auto summary = mcSummary(c.scenario, runs, keys);
  summary["cost"] = rig::campaignCost(c, runs);
  if (!slurm_submissions.empty()) {
    nlohmann::ordered_json jobs = nlohmann::ordered_json::array();
    for (const auto& s : slurm_submissions) jobs.push_back({{"submission", s.number}, {"job_id", s.job_id}});
    summary["slurm_jobs"] = jobs;
  }
  std::ofstream(fs::path(c.dir) / "mc.csv") << mcCsv(runs, keys);
  std::ofstream(fs::path(c.dir) / "mc_summary.json") << summary.dump(2) << "\n";
  for (const auto& run : runs) {
    if (!run.failure.empty() && !slurm_submissions.empty()) {
      std::cerr << "mc: run " << run.index << " (seed " << run.seed << ") failed: " << run.failure
                << (run.log.empty() ? "" : "; log " + run.log) << "\n";
    }
  }
  std::cout << "mc: " << summary["succeeded"] << " of " << c.runs << " runs succeeded ("
            << (fs::path(c.dir) / "mc.csv").string() << ", " << (fs::path(c.dir) / "mc_summary.json").string()
            << ")\n"
            << mcTable(summary);
  const auto& cost = summary["cost"];
  if (cost["overhead_fraction"].is_number()) {
    std::printf("mc: %.3f runs per CPU-second; the campaign's own CPU beyond its runs': %.2f %%\n",
                cost["runs_per_cpu_s"].get<double>(), 100.0 * cost["overhead_fraction"].get<double>());
  }
  return summary["succeeded"] == c.runs ? 0 : 1;
}

/// Submits `indices` to Slurm and, unless --no-wait, follows the job and gathers.
int runOnSlurm(const Campaign& c, const std::vector<int>& indices, const McOptions& o) {
  Submission s;
  try {
    s = submitRuns(c, indices, o.slurm);
  } catch (const std::exception& e) {
    std::cerr << "error: mc: " << e.what() << "\n";
    return 2;
  }
  std::cerr << "mc: submitted " << indices.size() << " runs of '" << c.name << "' as job " << s.job_id << " ("
            << s.tasks.size() << " array tasks of at most " << o.slurm.per_task << " runs; "
            << rig::submissionScript(c, s.number) << ")\n";
  if (o.no_wait) {
    std::cout << s.job_id << "\n";
    return 0;
  }
  const auto start = Clock::now();
  const bool followed = followJob(c, s);
  rig::writeRunnerCost(c, "submission-" + std::to_string(s.number) + "-submitter",
                       std::chrono::duration<double>(Clock::now() - start).count());
  if (!followed) return bus::shutdownRequested() ? 130 : 1;
  return gather(c);
}

int problemsExit(const std::vector<std::string>& problems) {
  for (const auto& p : problems) std::cerr << "error: mc: " << p << "\n";
  return 2;
}

/// --collect DIR: follows the campaign's newest job while it runs, then gathers.
int collect(const McOptions& o) {
  Campaign c;
  try {
    c = rig::readCampaign(o.collect);
  } catch (const std::exception& e) {
    return problemsExit({std::string("--collect: ") + e.what()});
  }
  const auto all = submissions(c);
  // Followed also when squeue did not answer: followJob waits for the controller.
  if (!all.empty() && jobActive(all.back().job_id).value_or(true)) {
    if (!followJob(c, all.back())) return bus::shutdownRequested() ? 130 : 1;
  }
  return gather(c);
}

/// --resume DIR: runs again only the runs with no successful end.
int resume(const McOptions& o) {
  if (!o.scenario.empty() || o.runs_given || !o.overrides.empty() || o.seed0) {
    return problemsExit({"--resume runs the campaign's own scenario, runs and seeds: give no scenario, --runs, "
                         "--set or --seed0"});
  }
  if (o.jobs < 1) return problemsExit({"--jobs " + std::to_string(o.jobs) + ": must be >= 1"});
  Campaign c;
  try {
    c = rig::readCampaign(o.resume);
  } catch (const std::exception& e) {
    return problemsExit({std::string("--resume: ") + e.what()});
  }
  if (c.version != kFlatsatVersion) {
    return problemsExit({o.resume + " was made by flatsat " + c.version + "; this is flatsat " + kFlatsatVersion +
                         ": resume it with that version, so that every run is the same program"});
  }
  const auto all = submissions(c);
  if (!all.empty()) {
    const auto active = jobActive(all.back().job_id);
    if (!active) {
      return problemsExit({"squeue did not answer about job " + all.back().job_id + " of this campaign: it may "
                           "still run, so no run of it is cleared; try again when the controller answers"});
    }
    if (*active) {
      return problemsExit({"job " + all.back().job_id + " of this campaign is still queued or running: flatsat mc "
                           "--collect " + o.resume + " follows it"});
    }
  }
  const auto missing = rig::unfinishedRuns(c);
  if (missing.empty()) {
    std::cerr << "mc: every run of " << c.dir << " has ended successfully; nothing to resume\n";
    return gather(c);
  }
  if (o.use_slurm) {
    if (const auto problems = slurmProblems(c.dir, missing.size(), o.slurm); !problems.empty()) {
      return problemsExit(problems);
    }
    return runOnSlurm(c, missing, o);
  }
  if (!runHere(c, missing, o.jobs)) {
    gather(c);
    return 130;
  }
  return gather(c);
}

int runCampaign(McOptions o) {
  if (!o.collect.empty()) return collect(o);
  if (!o.resume.empty()) return resume(o);
  if (o.jobs < 1) return problemsExit({"--jobs " + std::to_string(o.jobs) + ": must be >= 1"});
  if (o.scenario.empty()) return problemsExit({"a scenario is required (or --collect DIR, --resume DIR)"});
  bus::Scenario scenario;
  if (o.out.empty()) {
    try {
      o.out = defaultRunDirectory(bus::loadScenario(o.scenario).name + "-mc");
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 2;
    }
  }
  // Slurm is asked first: a campaign it cannot take leaves no directory behind.
  if (o.use_slurm) {
    const auto runs = static_cast<std::size_t>(std::max(0, o.runs));
    if (const auto problems = slurmProblems(o.out, runs, o.slurm); !problems.empty()) return problemsExit(problems);
  }
  const bool new_out = !fs::exists(o.out);
  if (const auto problems = checkCampaign(o, scenario); !problems.empty()) {
    if (new_out) fs::remove_all(o.out);
    return problemsExit(problems);
  }
  Campaign c;
  c.dir = fs::absolute(o.out).lexically_normal().string();
  c.scenario = o.scenario;
  c.name = scenario.name;
  c.runs = o.runs;
  c.seed0 = o.seed0.value_or(scenario.seed);
  c.version = kFlatsatVersion;
  c.executable = fs::canonical("/proc/self/exe").string();
  rig::writeCampaign(c);
  std::cerr << "mc: campaign of " << c.runs << " runs, seeds " << c.seed0 << ".."
            << c.seed0 + static_cast<std::uint64_t>(c.runs - 1) << "\n";
  std::vector<int> all(static_cast<std::size_t>(c.runs));
  for (int i = 0; i < c.runs; ++i) all[static_cast<std::size_t>(i)] = i;
  if (o.use_slurm) return runOnSlurm(c, all, o);
  const bool completed = runHere(c, all, o.jobs);
  const int result = gather(c);
  return completed ? result : 130;
}

}  // namespace

CLI::App* addMcCommand(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<McOptions>();
  auto* mc = app.add_subcommand("mc", "Monte Carlo: seeded composed runs in parallel (or on Slurm), one table");
  mc->add_option("scenario", o->scenario, "scenario file (YAML) or name")->transform(scenarioByName());
  auto* runs = mc->add_option("--runs", o->runs, "number of runs");
  mc->add_option("--jobs", o->jobs, "runs at a time on this host")->capture_default_str();
  mc->add_option("--out", o->out, "campaign directory (default runs/<name>-mc-<time>)");
  mc->add_option("--seed0", o->seed0, "seed of run 0; run i has seed0 + i (default: the scenario's seed)");
  mc->add_option("--set", o->overrides, "override a scenario key in every run: key.path=value");
  mc->add_flag("--slurm", o->use_slurm, "submit the runs to Slurm as one job array (sbatch) and follow it");
  mc->add_option("--per-task", o->slurm.per_task, "with --slurm: runs per array task")->capture_default_str();
  mc->add_option("--partition", o->slurm.partition, "with --slurm: the partition (default: the cluster's)");
  mc->add_option("--time", o->slurm.time_limit, "with --slurm: each array task's time limit (sbatch --time)");
  mc->add_flag("--no-wait", o->no_wait, "with --slurm: submit, print the job id and return");
  mc->add_option("--collect", o->collect, "gather campaign DIR (following its Slurm job while it runs)");
  mc->add_option("--resume", o->resume, "run again the runs of campaign DIR that did not succeed");
  mc->callback([o, runs, &exit_code] {
    if (!o->use_slurm && (o->no_wait || o->slurm.per_task != 1 || !o->slurm.partition.empty() ||
                          !o->slurm.time_limit.empty())) {
      std::cerr << "error: mc: --per-task, --partition, --time and --no-wait go with --slurm\n";
      exit_code = 2;
      return;
    }
    o->runs_given = runs->count() > 0;
    if (o->collect.empty() && o->resume.empty() && (o->scenario.empty() || !o->runs_given)) {
      std::cerr << "error: mc: give a scenario and --runs N (or --collect DIR, --resume DIR)\n";
      exit_code = 2;
      return;
    }
    exit_code = runCampaign(*o);
  });

  // What each Slurm array task runs on its node (the batch script calls it).
  struct TaskOptions {
    std::string dir;
    int submission = 0;
    int task = -1;
  };
  auto t = std::make_shared<TaskOptions>();
  auto* task = app.add_subcommand("mc-task", "one array task of a Slurm campaign (run by its batch script)");
  task->group("");  // not listed: users never call it
  task->add_option("dir", t->dir, "campaign directory")->required();
  task->add_option("--submission", t->submission, "submission number")->required();
  task->add_option("--task", t->task, "array task index")->required();
  task->callback([t, &exit_code] { exit_code = runArrayTask(t->dir, t->submission, t->task, kFlatsatVersion); });
  return mc;
}

}  // namespace flatsat::tools
