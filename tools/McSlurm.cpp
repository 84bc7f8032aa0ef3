// SPDX-License-Identifier: Apache-2.0
#include "tools/McSlurm.hpp"

#include <signal.h>
#include <sys/statfs.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "bus/Bus.hpp"
#include "bus/Shutdown.hpp"
#include "rig/JsonFile.hpp"
#include "rig/Spawn.hpp"

namespace flatsat::tools {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using rig::Campaign;
using rig::runCaptured;

namespace {

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::string firstLine(const std::string& text) {
  const auto end = text.find('\n');
  return text.substr(0, end);
}

/// A node is this host when Slurm names it or addresses it as this host.
bool isThisHost(const std::string& name, const std::string& host_name, const std::string& address) {
  static const auto own = bus::ownAddresses();
  const std::string me = rig::hostName();
  const std::string me_short = me.substr(0, me.find('.'));
  for (const auto& n : {name, host_name}) {
    if (n == "localhost" || n == me || n == me_short) return true;
  }
  if (address.rfind("127.", 0) == 0 || address == "::1" || address == "localhost") return true;
  return std::find(own.begin(), own.end(), address) != own.end();
}

/// The partition's nodes that are other hosts; std::nullopt (and a problem)
/// when the partition is unknown.
std::optional<std::vector<std::string>> remoteNodes(const std::string& partition,
                                                    std::vector<std::string>& problems) {
  std::string name = partition;
  if (name.empty()) {
    const auto list = runCaptured({"sinfo", "-h", "-o", "%P"});
    for (const auto& p : words(list.out)) {
      if (!p.empty() && p.back() == '*') name = p.substr(0, p.size() - 1);
    }
    if (name.empty()) {
      problems.push_back("the cluster has no default partition (sinfo: " + firstLine(list.err + list.out) +
                         "); name one with --partition");
      return std::nullopt;
    }
  }
  const auto nodes = runCaptured({"sinfo", "-h", "-N", "-p", name, "-o", "%N %n %o"});
  if (nodes.exit_code != 0) {
    problems.push_back("sinfo cannot list partition '" + name + "': " + firstLine(nodes.err));
    return std::nullopt;
  }
  if (words(nodes.out).empty()) {
    const auto all = runCaptured({"sinfo", "-h", "-o", "%P"});
    std::string known;
    for (auto p : words(all.out)) {
      if (!p.empty() && p.back() == '*') p.pop_back();
      known += (known.empty() ? "" : ", ") + p;
    }
    problems.push_back("--partition " + name + ": no such partition (this cluster has: " + known + ")");
    return std::nullopt;
  }
  std::vector<std::string> remote;
  std::istringstream lines(nodes.out);
  for (std::string line; std::getline(lines, line);) {
    const auto w = words(line);
    if (w.size() < 3) continue;
    if (!isThisHost(w[0], w[1], w[2]) && std::find(remote.begin(), remote.end(), w[0]) == remote.end()) {
      remote.push_back(w[0]);
    }
  }
  return remote;
}

/// The cluster's MaxArraySize (scontrol show config); 0 when unknown.
long maxArraySize() {
  const auto config = runCaptured({"scontrol", "show", "config"});
  std::istringstream lines(config.out);
  for (std::string line; std::getline(lines, line);) {
    const auto w = words(line);
    if (w.size() >= 3 && w[0] == "MaxArraySize" && w[1] == "=") return std::atol(w[2].c_str());
  }
  return 0;
}

int endedRuns(const Campaign& c, const Submission& s, int& failed) {
  int ended = 0;
  failed = 0;
  for (const auto& task : s.tasks) {
    for (const int run : task) {
      if (const auto status = rig::readRunStatus(c, run)) {
        ++ended;
        failed += status->exit_code != 0 ? 1 : 0;
      }
    }
  }
  return ended;
}

}  // namespace

std::vector<std::string> slurmProblems(const std::string& dir, std::size_t runs, const rig::SlurmJobOptions& o) {
  std::vector<std::string> problems;
  for (const char* tool : {"sbatch", "squeue", "sinfo", "scontrol"}) {
    if (!rig::onPath(tool)) {
      problems.push_back(std::string(tool) +
                         " is not on PATH: submit from a host with Slurm's client commands (a login node), or "
                         "run the campaign here without --slurm");
    }
  }
  if (o.per_task < 1) problems.push_back("--per-task " + std::to_string(o.per_task) + ": must be >= 1");
  if (!o.time_limit.empty() && !rig::validTimeLimit(o.time_limit)) {
    problems.push_back("--time " + o.time_limit +
                       ": not a Slurm time limit (minutes, M:S, H:M:S, D-H, D-H:M, D-H:M:S or UNLIMITED)");
  }
  // The whole path goes on #SBATCH lines, which sbatch splits at blanks and
  // whose --output expands '%' patterns (sbatch(1), "filename pattern").
  const std::string absolute = fs::absolute(dir).lexically_normal().string();
  if (absolute.find_first_of(" \t\n'\"%\\") != std::string::npos) {
    problems.push_back("--out " + absolute +
                       ": a Slurm campaign directory cannot hold blanks, quotes, '%' or '\\' (#SBATCH lines)");
  }
  if (!problems.empty()) return problems;
  const auto remote = remoteNodes(o.partition, problems);
  if (!remote) return problems;
  const std::size_t tasks = rig::splitIntoTasks(std::vector<int>(runs, 0), o.per_task).size();
  if (const long max = maxArraySize(); max > 0 && static_cast<long>(tasks) > max) {
    problems.push_back(std::to_string(tasks) + " array tasks exceed this cluster's MaxArraySize " +
                       std::to_string(max) + " (indices up to " + std::to_string(max - 1) +
                       "): give a larger --per-task");
  }
  fs::path existing = fs::absolute(dir);
  while (!fs::exists(existing) && existing.has_parent_path() && existing != existing.parent_path()) {
    existing = existing.parent_path();
  }
  struct statfs info {};
  if (::statfs(existing.c_str(), &info) != 0) {
    problems.push_back("--out " + dir + ": cannot read its filesystem");
  } else if (const auto problem = rig::sharedDirectoryProblem(dir, static_cast<long>(info.f_type), *remote);
             !problem.empty()) {
    problems.push_back(problem);
  }
  return problems;
}

Submission submitRuns(const Campaign& c, const std::vector<int>& runs, const rig::SlurmJobOptions& o) {
  Submission s;
  s.number = static_cast<int>(submissions(c).size()) + 1;
  s.tasks = rig::splitIntoTasks(runs, o.per_task);
  for (const auto& task : s.tasks) {
    for (const int run : task) rig::clearRun(c, run);
  }
  fs::create_directories(fs::path(rig::taskOutput(c, s.number, 0)).parent_path());
  const std::string script = rig::submissionScript(c, s.number);
  std::ofstream(script) << rig::batchScript(c, s.number, s.tasks.size(), o);
  rig::writeJsonAtomically(rig::submissionRecord(c, s.number), {{"job_id", ""}, {"tasks", s.tasks}});
  const auto sbatch = runCaptured({"sbatch", "--parsable", script});
  if (sbatch.exit_code != 0) {
    // Nothing was submitted: no record of a submission is left to be followed or resumed.
    const std::string reason = firstLine(sbatch.err + sbatch.out);
    fs::remove(rig::submissionRecord(c, s.number));
    fs::remove(script);
    throw std::runtime_error("sbatch refused the job array: " + reason);
  }
  // --parsable: "jobid" or "jobid;cluster".
  s.job_id = firstLine(sbatch.out).substr(0, firstLine(sbatch.out).find(';'));
  rig::writeJsonAtomically(rig::submissionRecord(c, s.number), {{"job_id", s.job_id}, {"tasks", s.tasks}});
  return s;
}

std::vector<Submission> submissions(const Campaign& c) {
  std::vector<Submission> out;
  for (int n = 1; fs::exists(rig::submissionRecord(c, n)); ++n) {
    const auto j = rig::readJsonFile(rig::submissionRecord(c, n));
    out.push_back({n, j.at("job_id").get<std::string>(), j.at("tasks").get<std::vector<std::vector<int>>>()});
  }
  return out;
}

std::optional<bool> jobActive(const std::string& job_id) {
  const auto q = runCaptured({"squeue", "-h", "-r", "-j", job_id, "-o", "%i %T"});
  if (q.exit_code != 0) {
    // squeue answers an id it no longer holds with this error: the job is over.
    if ((q.err + q.out).find("Invalid job id") != std::string::npos) return false;
    return std::nullopt;  // the controller did not answer: the job may still run
  }
  const auto progress = rig::parseSqueue(q.out);
  return progress.pending + progress.running > 0;
}

bool followJob(const Campaign& c, const Submission& s) {
  const auto start = Clock::now();
  const bool terminal = ::isatty(STDERR_FILENO) == 1;
  bool unreachable = false;
  Clock::time_point unreachable_since{};
  std::string last;
  while (true) {
    const auto q = runCaptured({"squeue", "-h", "-r", "-j", s.job_id, "-o", "%i %T"});
    // A job squeue no longer knows has ended (it forgets them MinJobAge after).
    const bool gone = q.exit_code != 0 && q.err.find("Invalid job id") != std::string::npos;
    if (q.exit_code != 0 && !gone) {
      if (!unreachable) {
        unreachable = true;
        unreachable_since = Clock::now();
        std::cerr << "mc: squeue failed (" << firstLine(q.err) << "); retrying\n";
      } else if (Clock::now() - unreachable_since > std::chrono::minutes(5)) {
        std::cerr << "mc: squeue has failed for 5 minutes; job " << s.job_id
                  << " may still run: flatsat mc --collect " << c.dir << " gathers it later\n";
        return false;
      }
    } else {
      unreachable = false;
    }
    const auto tasks = rig::parseSqueue(q.exit_code == 0 ? q.out : "");
    int failed = 0;
    const int ended = endedRuns(c, s, failed);
    int runs = 0;
    for (const auto& task : s.tasks) runs += static_cast<int>(task.size());
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    char line[200];
    std::snprintf(line, sizeof line, "mc: job %s: %d tasks pending, %d running; %d/%d runs ended, %d failed, %.0f s",
                  s.job_id.c_str(), tasks.pending, tasks.running, ended, runs, failed, elapsed);
    const bool done = gone || (q.exit_code == 0 && tasks.pending + tasks.running == 0);
    // On a terminal the line is rewritten; in a log, written when it changes.
    const std::string changed = std::string(line).substr(0, std::string(line).rfind(','));
    if (terminal) {
      std::fprintf(stderr, "\r%s   %s", line, done ? "\n" : "");
    } else if (changed != last || done) {
      std::fprintf(stderr, "%s\n", line);
    }
    last = changed;
    if (done) return true;
    // Polls the controller gently: a campaign of hours need not ask every second.
    const auto pause = elapsed < 60 ? std::chrono::milliseconds(1000) : std::chrono::milliseconds(10000);
    for (auto waited = std::chrono::milliseconds(0); waited < pause; waited += std::chrono::milliseconds(100)) {
      if (bus::shutdownRequested()) {
        std::cerr << (terminal ? "\n" : "") << "mc: stopped following; job " << s.job_id
                  << " carries on: flatsat mc --collect " << c.dir << " gathers it (scancel " << s.job_id
                  << " stops it)\n";
        return false;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
}

void explainSlurmFailures(const Campaign& c, std::vector<analysis::McRun>& runs) {
  const auto all = submissions(c);
  for (auto& run : runs) {
    if (run.failure.empty()) continue;
    for (auto s = all.rbegin(); s != all.rend(); ++s) {
      const auto task = std::find_if(s->tasks.begin(), s->tasks.end(), [&](const std::vector<int>& t) {
        return std::find(t.begin(), t.end(), run.index) != t.end();
      });
      if (task == s->tasks.end()) continue;
      const int t = static_cast<int>(task - s->tasks.begin());
      const std::string output = rig::taskOutput(c, s->number, t);
      std::ifstream in(output);
      const std::string text((std::istreambuf_iterator<char>(in)), {});
      const std::string reason = rig::taskEndReason(text);
      const std::string where = "array task " + std::to_string(t) + " of job " + s->job_id;
      if (!in) {
        run.failure += "; " + where + " left no output (" + output +
                       "): cancelled before it started, or the directory is not shared with its node";
      } else {
        run.failure += "; " + where + (reason.empty() ? " gave no reason" : ": " + reason) + " (" + output + ")";
      }
      break;
    }
  }
}

int runArrayTask(const std::string& dir, int submission, int task, const std::string& version) {
  const auto start = Clock::now();
  Campaign c;
  std::vector<int> runs;
  try {
    c = rig::readCampaign(dir);
    if (c.version != version) {
      throw std::runtime_error(dir + " was written by flatsat " + c.version + ", but " + rig::hostName() +
                               " runs flatsat " + version + ": install the same flatsat on every node");
    }
    const auto all = submissions(c);
    if (submission < 1 || submission > static_cast<int>(all.size())) {
      throw std::runtime_error(rig::submissionRecord(c, submission) + ": no such submission");
    }
    const auto& tasks = all[static_cast<std::size_t>(submission - 1)].tasks;
    if (task < 0 || task >= static_cast<int>(tasks.size())) {
      throw std::runtime_error("--task " + std::to_string(task) + ": submission " + std::to_string(submission) +
                               " has " + std::to_string(tasks.size()) + " tasks");
    }
    runs = tasks[static_cast<std::size_t>(task)];
  } catch (const std::exception& e) {
    std::cerr << "error: mc-task: " << e.what() << "\n";
    return 2;
  }
  std::cerr << "mc-task: submission " << submission << " task " << task << " on " << rig::hostName() << ": "
            << runs.size() << " runs\n";
  int failed = 0;
  for (const int index : runs) {
    if (bus::shutdownRequested()) break;
    // A task Slurm requeued (its node failed) starts its runs afresh.
    rig::clearRun(c, index);
    std::vector<rig::StartedRun> running;
    try {
      running.push_back(rig::startRun(c, index));
    } catch (const std::runtime_error& e) {
      std::cerr << "error: mc-task: run " << index << ": " << e.what() << "\n";
      return 1;
    }
    std::optional<std::pair<int, rig::RunStatus>> ended;
    bool told = false;
    while (!(ended = rig::waitForRun(c, running)) && !running.empty()) {
      // Slurm signals the whole task on scancel; the run stops and its end is still recorded.
      if (bus::shutdownRequested() && !told) {
        ::kill(running.front().pid, SIGTERM);
        told = true;
      }
    }
    if (!ended) continue;
    failed += ended->second.exit_code != 0 || !ended->second.unrecorded.empty() ? 1 : 0;
    std::cerr << "mc-task: run " << index << " (seed " << rig::runSeed(c, index) << ") ended with exit status "
              << ended->second.exit_code << " after " << ended->second.wall_s << " s\n";
    if (!ended->second.unrecorded.empty()) {
      std::cerr << "error: mc-task: run " << index << ": its end is not recorded: " << ended->second.unrecorded << "\n";
    }
  }
  rig::writeRunnerCost(c, "submission-" + std::to_string(submission) + "-task-" + std::to_string(task),
                       std::chrono::duration<double>(Clock::now() - start).count());
  return failed == 0 && !bus::shutdownRequested() ? 0 : 1;
}

}  // namespace flatsat::tools
