// SPDX-License-Identifier: Apache-2.0
#include "rig/Campaign.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "rig/JsonFile.hpp"
#include "rig/Spawn.hpp"

namespace flatsat::rig {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

std::string campaignFile(const std::string& dir) { return (fs::path(dir) / "campaign.json").string(); }
std::string statusFile(const Campaign& c, int index) {
  return (fs::path(runDirectory(c, index)) / "run_status.json").string();
}


template <typename T>
T required(const Json& j, const char* key, const std::string& file) {
  if (!j.contains(key)) throw std::runtime_error(file + ": no key '" + key + "'");
  try {
    return j.at(key).get<T>();
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(file + ": key '" + key + "': " + e.what());
  }
}

}  // namespace

void writeCampaign(const Campaign& c) {
  writeJsonAtomically(campaignFile(c.dir), Json{{"scenario", c.scenario},
                                            {"name", c.name},
                                            {"runs", c.runs},
                                            {"seed0", c.seed0},
                                            {"version", c.version},
                                            {"executable", c.executable}});
}

Campaign readCampaign(const std::string& dir) {
  const std::string file = campaignFile(dir);
  const Json j = readJsonFile(file, "not a campaign directory, or not shared with this host");
  Campaign c;
  c.dir = fs::absolute(dir).lexically_normal().string();
  c.scenario = required<std::string>(j, "scenario", file);
  c.name = required<std::string>(j, "name", file);
  c.runs = required<int>(j, "runs", file);
  c.seed0 = required<std::uint64_t>(j, "seed0", file);
  c.version = required<std::string>(j, "version", file);
  c.executable = required<std::string>(j, "executable", file);
  if (c.runs < 1) throw std::runtime_error(file + ": key 'runs': must be >= 1");
  return c;
}

std::string runDirectory(const Campaign& c, int index) {
  return (fs::path(c.dir) / ("run-" + std::to_string(index))).string();
}
std::string runLog(const Campaign& c, int index) {
  return (fs::path(c.dir) / ("run-" + std::to_string(index) + ".log")).string();
}
std::uint64_t runSeed(const Campaign& c, int index) { return c.seed0 + static_cast<std::uint64_t>(index); }

std::vector<std::string> runArguments(const Campaign& c, int index) {
  return {c.executable, "run",          (fs::path(c.dir) / "scenario.yaml").string(),
          "--composed", "--seed",       std::to_string(runSeed(c, index)),
          "--no-plots", "-q",           "--out",
          runDirectory(c, index)};
}

void clearRun(const Campaign& c, int index) {
  fs::remove_all(runDirectory(c, index));
  fs::remove(runLog(c, index));
}

StartedRun startRun(const Campaign& c, int index) {
  return {index, spawnLogged(runArguments(c, index), runLog(c, index)), std::chrono::steady_clock::now()};
}

std::optional<std::pair<int, RunStatus>> waitForRun(const Campaign& c, std::vector<StartedRun>& running) {
  int status = 0;
  rusage usage{};
  const pid_t pid = ::wait4(-1, &status, 0, &usage);
  if (pid < 0) return std::nullopt;
  const auto it = std::find_if(running.begin(), running.end(), [&](const StartedRun& r) { return r.pid == pid; });
  if (it == running.end()) return waitForRun(c, running);  // not a run of ours
  RunStatus end;
  end.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  end.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - it->started).count();
  end.cpu_s = cpuSeconds(usage);
  end.host = hostName();
  const int index = it->index;
  running.erase(it);
  // The child is reaped: a full disk must not lose it from the caller's count.
  try {
    fs::create_directories(runDirectory(c, index));
    writeJsonAtomically(statusFile(c, index), Json{{"exit_code", end.exit_code},
                                                   {"wall_s", end.wall_s},
                                                   {"cpu_s", end.cpu_s},
                                                   {"host", end.host}});
  } catch (const std::exception& e) {
    end.unrecorded = e.what();
  }
  return std::make_pair(index, end);
}

std::optional<RunStatus> readRunStatus(const Campaign& c, int index) {
  std::ifstream in(statusFile(c, index));
  if (!in) return std::nullopt;
  try {
    Json j;
    in >> j;
    return RunStatus{j.at("exit_code").get<int>(), j.at("wall_s").get<double>(), j.at("cpu_s").get<double>(),
                     j.at("host").get<std::string>()};
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // torn by a crash of its writer: the run has no end on record
  }
}

analysis::McRun gatherRun(const Campaign& c, int index) {
  analysis::McRun run;
  run.index = index;
  run.seed = runSeed(c, index);
  const auto status = readRunStatus(c, index);
  const fs::path summary_file = fs::path(runDirectory(c, index)) / "summary.json";
  if (status && status->exit_code == 0 && fs::exists(summary_file)) {
    run.exit_code = 0;
    try {
      std::ifstream(summary_file) >> run.summary;
      fs::remove(runLog(c, index));  // the run directory holds its own logs
      return run;
    } catch (const nlohmann::json::exception& e) {
      run.summary = nullptr;
      run.failure = summary_file.string() + ": " + e.what();
    }
  } else if (status) {
    run.exit_code = status->exit_code;
    run.failure = "exit status " + std::to_string(status->exit_code) + " on " + status->host;
  } else {
    run.failure = "no end recorded";
  }
  if (fs::exists(runLog(c, index))) run.log = runLog(c, index);
  return run;
}

std::vector<int> unfinishedRuns(const Campaign& c) {
  std::vector<int> out;
  for (int i = 0; i < c.runs; ++i) {
    const auto status = readRunStatus(c, i);
    if (!status || status->exit_code != 0 || !fs::exists(fs::path(runDirectory(c, i)) / "summary.json")) {
      out.push_back(i);
    }
  }
  return out;
}

void writeRunnerCost(const Campaign& c, const std::string& runner, double wall_s) {
  rusage self{}, children{};
  ::getrusage(RUSAGE_SELF, &self);
  ::getrusage(RUSAGE_CHILDREN, &children);
  fs::create_directories(fs::path(c.dir) / "cost");
  writeJsonAtomically((fs::path(c.dir) / "cost" / (runner + ".json")).string(),
                  Json{{"runner", runner},
                       {"host", hostName()},
                       {"cpu_s", cpuSeconds(self) + cpuSeconds(children)},
                       {"wall_s", wall_s}});
}

Json campaignCost(const Campaign& c, const std::vector<analysis::McRun>& runs) {
  double runs_cpu = 0, runners_cpu = 0;
  int ended = 0, succeeded = 0;
  for (int i = 0; i < c.runs; ++i) {
    if (const auto status = readRunStatus(c, i)) {
      runs_cpu += status->cpu_s;
      ++ended;
    }
  }
  for (const auto& run : runs) succeeded += run.failure.empty() ? 1 : 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(fs::path(c.dir) / "cost", ec)) {
    if (entry.path().extension() != ".json") continue;
    try {
      Json j;
      std::ifstream(entry.path()) >> j;
      runners_cpu += j.at("cpu_s").get<double>();
    } catch (const nlohmann::json::exception&) {
      // A runner that crashed mid-write: its CPU is unknown, not zero.
    }
  }
  Json cost{{"runs_ended", ended}, {"runs_cpu_s", runs_cpu}, {"runners_cpu_s", runners_cpu}};
  cost["overhead_fraction"] = runs_cpu > 0 && runners_cpu > 0 ? Json((runners_cpu - runs_cpu) / runs_cpu) : Json();
  cost["runs_per_cpu_s"] = runners_cpu > 0 ? Json(succeeded / runners_cpu) : Json();
  return cost;
}

std::string hostName() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

}  // namespace flatsat::rig
