// SPDX-License-Identifier: Apache-2.0
#include "tools/ScenarioName.hpp"
#include "bus/InstallPaths.hpp"
#include "tools/SoakCommand.hpp"

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "bus/Recording.hpp"
#include "bus/Scenario.hpp"
#include "bus/Serialization.hpp"
#include "bus/Shutdown.hpp"
#include "bus/Topics.hpp"
#include "rig/Spawn.hpp"

namespace flatsat::tools {

using rig::spawnLogged;

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct SoakOptions {
  std::string scenario = bus::installedScenario("default.yaml");
  double minutes = 10.0;                    // [min] run length, > 1
  std::vector<double> kill_every_s{3, 8};   // [s] MIN MAX between kills
  std::uint64_t seed = 1;
  std::string out;                          // run directory; default runs/soak-<pid>
  std::vector<std::string> overrides;
};

/// component name -> pid of the processes `flatsat run` started into `run_dir`.
std::map<std::string, pid_t> rigProcesses(const std::string& run_dir) {
  std::map<std::string, pid_t> found;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const auto pid = entry.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream in(entry.path() / "cmdline", std::ios::binary);
    std::vector<std::string> argv;
    for (std::string arg; std::getline(in, arg, '\0');) argv.push_back(arg);
    std::string name, out;
    for (std::size_t i = 0; i + 1 < argv.size(); ++i) {
      if (argv[i] == "--name") name = argv[i + 1];
      if (argv[i] == "--out") out = argv[i + 1];
    }
    if (!name.empty() && out == run_dir && fs::path(argv[0]).filename().string().rfind("flatsat-", 0) == 0) {
      found[name] = std::stoi(pid);
    }
  }
  return found;
}

/// [KiB] VmRSS of a process, 0 when it is gone.
std::uint64_t residentKiB(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6));
  }
  return 0;
}

struct Memory {
  pid_t pid;
  std::uint64_t start_kib;
  std::uint64_t end_kib = 0;
  bool same_process = false;  // not restarted in between
};

std::string readFile(const fs::path& path) {
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  return text.str();
}

/// The steps a component's log says it did ("<name>: stopped after N steps"), -1 if none.
long long stepsDone(const fs::path& log, const std::string& name) {
  const std::string text = readFile(log);
  const std::string marker = name + ": stopped after ";
  const auto at = text.rfind(marker);
  return at == std::string::npos ? -1 : std::stoll(text.substr(at + marker.size()));
}

/// The `flatsat run` child.
struct RunProcess {
  pid_t pid;
  bool done = false;
  int status = 0;
  bool alive() {
    if (!done && waitpid(pid, &status, WNOHANG) == pid) done = true;
    return !done;
  }
  void wait() {
    if (!done && waitpid(pid, &status, 0) == pid) done = true;
  }
};

/// Sleeps until `until` unless the run ends or an interrupt stops it; false then.
bool waitUntil(Clock::time_point until, RunProcess& run) {
  while (Clock::now() < until) {
    if (bus::shutdownRequested()) {
      kill(run.pid, SIGTERM);
      return false;
    }
    if (!run.alive()) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return true;
}

int runSoak(const SoakOptions& o) {
  if (o.kill_every_s.size() != 2 || !(o.kill_every_s[0] > 0 && o.kill_every_s[0] <= o.kill_every_s[1]) ||
      !(o.minutes >= 1.0)) {
    std::cerr << "error: soak: need --minutes >= 1 and --kill-every-s MIN MAX with 0 < MIN <= MAX\n";
    return 2;
  }
  bus::installShutdownHandlers();
  const std::string run_dir = fs::absolute(o.out.empty() ? "runs/soak-" + std::to_string(::getpid()) : o.out);
  fs::create_directories(run_dir);
  const double duration_s = o.minutes * 60.0;
  std::vector<std::string> argv{fs::canonical("/proc/self/exe").string(), "run", o.scenario, "-q", "--no-plots",
                                "--restart", "--max-restarts", "1000000", "--out", run_dir, "--set", "mode=paced", "--set",
                                "duration_orbits=null", "--set", "duration_s=" + std::to_string(duration_s)};
  for (const auto& s : o.overrides) argv.insert(argv.end(), {"--set", s});
  RunProcess run{spawnLogged(argv, run_dir + ".log")};
  std::printf("soak: '%s' paced for %.1f min into %s, a kill every %.1f..%.1f s (seed %llu)\n", o.scenario.c_str(),
              o.minutes, run_dir.c_str(), o.kill_every_s[0], o.kill_every_s[1],
              static_cast<unsigned long long>(o.seed));
  std::fflush(stdout);

  // Ready: the time master grants step 0.
  const auto launched = Clock::now();
  while (readFile(fs::path(run_dir) / "logs" / "dynamics_server.log").find("every component ready") ==
         std::string::npos) {
    if (Clock::now() - launched > std::chrono::seconds(120) || !waitUntil(Clock::now() + std::chrono::milliseconds(200), run)) {
      kill(run.pid, SIGTERM);
      run.wait();
      std::cerr << "error: soak: the rig did not start; see " << run_dir << ".log\n";
      return 1;
    }
  }
  const auto started = Clock::now();
  const auto at = [&](double s) { return started + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s)); };
  bool running = waitUntil(at(10.0), run);
  std::map<std::string, Memory> memory;
  for (const auto& [name, pid] : rigProcesses(run_dir)) memory[name] = {pid, residentKiB(pid)};
  std::vector<std::string> victims;
  for (const auto& [name, m] : memory) {
    if (name != "dynamics_server" && name != "recorder") victims.push_back(name);
  }

  std::mt19937_64 random(o.seed);
  std::uniform_real_distribution<double> interval(o.kill_every_s[0], o.kill_every_s[1]);
  std::map<std::string, int> kills;
  double t = 10.0 + interval(random);
  while (running && !victims.empty() && t < duration_s - 15.0) {
    if (!(running = waitUntil(at(t), run))) break;
    const std::string& victim = victims[std::uniform_int_distribution<std::size_t>(0, victims.size() - 1)(random)];
    const auto pids = rigProcesses(run_dir);
    if (auto it = pids.find(victim); it != pids.end() && kill(it->second, SIGKILL) == 0) ++kills[victim];
    t += interval(random);
  }
  if (running) running = waitUntil(at(duration_s - 10.0), run);
  for (const auto& [name, pid] : rigProcesses(run_dir)) {
    if (auto it = memory.find(name); it != memory.end()) {
      it->second.end_kib = residentKiB(pid);
      it->second.same_process = pid == it->second.pid;
    }
  }
  run.wait();
  const bool completed = WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0;

  nlohmann::ordered_json report;
  std::vector<std::string> failed;
  const auto check = [&](bool ok, const std::string& what) {
    if (!ok) failed.push_back(what);
  };
  check(completed, "the run completed (see " + run_dir + ".log)");
  if (!completed) {
    report["failed"] = failed;
    std::ofstream(fs::path(run_dir) / "soak.json") << report.dump(2) << "\n";
    std::printf("soak: FAILED: the run did not complete; see %s.log\n", run_dir.c_str());
    return 1;
  }
  const auto summary = nlohmann::json::parse(readFile(fs::path(run_dir) / "summary.json"));
  const bus::Scenario scenario = bus::loadScenario((fs::path(run_dir) / "scenario.yaml").string());
  const bus::Recording recording(run_dir + "/recording.sqlite", bus::Recording::Access::kRead);

  std::map<std::string, int> restarted_events;
  using EventDef = std::remove_cvref_t<decltype(bus::topics::kFaultEvent)>;
  recording.forEach(std::string(bus::topics::kFaultEvent.name),
                    [&](std::uint64_t, const std::string& source, const std::vector<std::uint8_t>& bytes) {
                      if (bus::text(bus::deserialize<EventDef>(bytes).kind()) == "restarted") ++restarted_events[source];
                    });
  std::printf("\n%-22s %6s %9s %7s %12s %12s %9s\n", "COMPONENT", "KILLS", "RESTARTS", "EVENTS", "RSS START",
              "RSS END", "GROWTH");
  for (const auto& [name, m] : memory) {
    const int k = kills.count(name) ? kills.at(name) : 0;
    const int restarts = summary.contains("restarts") && summary["restarts"].contains(name)
                             ? summary["restarts"][name].get<int>() : 0;
    const int events = restarted_events.count(name) ? restarted_events.at(name) : 0;
    check(restarts == k, name + ": " + std::to_string(k) + " kills, " + std::to_string(restarts) + " restarts");
    check(events == k, name + ": " + std::to_string(k) + " kills, " + std::to_string(events) + " restarted events");
    const double growth = m.same_process ? static_cast<double>(m.end_kib) - static_cast<double>(m.start_kib) : 0.0;
    if (m.same_process) {
      check(growth <= std::max(0.10 * static_cast<double>(m.start_kib), 4096.0),
            name + ": resident memory grew from " + std::to_string(m.start_kib) + " to " + std::to_string(m.end_kib) +
                " KiB");
    }
    std::printf("%-22s %6d %9d %7d %9llu KiB %9llu KiB %9s\n", name.c_str(), k, restarts, events,
                static_cast<unsigned long long>(m.start_kib), static_cast<unsigned long long>(m.end_kib),
                m.same_process ? (std::to_string(static_cast<long long>(growth)) + " KiB").c_str() : "restarted");
    report["components"][name] = {{"kills", k}, {"restarts", restarts}, {"restarted_events", events},
                                  {"rss_start_kib", m.start_kib}, {"rss_end_kib", m.end_kib},
                                  {"same_process", m.same_process}};
  }

  // Every stepped sample once; what each producer did, all of it.
  std::printf("\n%-28s %-22s %8s %8s %10s\n", "TOPIC", "SOURCE", "SAMPLES", "TWICE", "STEPS DONE");
  bus::forEachTopic([&](const auto& def) {
    if (def.qos != bus::QosKind::kStepped) return;
    const std::string topic(def.name);
    std::map<std::string, std::set<std::uint64_t>> steps;
    std::map<std::string, std::uint64_t> rows, twice;
    recording.forEach(topic, [&](std::uint64_t step, const std::string& source, const std::vector<std::uint8_t>&) {
      ++rows[source];
      twice[source] += !steps[source].insert(step).second;
    });
    for (const auto& [source, n] : rows) {
      const bool killed = kills.count(source) != 0;
      long long done = -1;
      if (source == "dynamics_server") {
        done = std::llround(duration_s / scenario.step_s) + 1;  // steps 0..final (dynamics_server::readParams)
      } else if (!killed) {
        done = stepsDone(fs::path(run_dir) / "logs" / (source + ".log"), source);
      }
      check(twice[source] == 0, topic + " from " + source + ": " + std::to_string(twice[source]) + " samples twice");
      if (done >= 0) {
        check(static_cast<long long>(n) == done, topic + " from " + source + ": " + std::to_string(n) +
                                                     " samples recorded of " + std::to_string(done) + " steps done");
      }
      std::printf("%-28s %-22s %8llu %8llu %10s\n", topic.c_str(), source.c_str(), static_cast<unsigned long long>(n),
                  static_cast<unsigned long long>(twice[source]),
                  killed ? "restarted" : std::to_string(done).c_str());
      report["topics"][topic][source] = {{"samples", n}, {"twice", twice[source]}, {"steps_done", done}};
    }
  });
  report["minutes"] = o.minutes;
  report["seed"] = o.seed;
  report["failed"] = failed;
  std::ofstream(fs::path(run_dir) / "soak.json") << report.dump(2) << "\n";
  int total_kills = 0;
  for (const auto& [name, k] : kills) total_kills += k;
  if (!failed.empty()) {
    std::printf("\nsoak: FAILED:\n");
    for (const auto& f : failed) std::printf("  %s\n", f.c_str());
    return 1;
  }
  std::printf("\nsoak: passed: %d kills, every one restarted and recorded, nothing recorded twice or lost, "
              "memory flat (%s/soak.json)\n", total_kills, run_dir.c_str());
  return 0;
}

}  // namespace

CLI::App* addSoakCommand(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SoakOptions>();
  auto* soak = app.add_subcommand("soak", "paced run with random SIGKILL/restart of components, then checks");
  soak->add_option("scenario", o->scenario, "scenario file or name")->transform(scenarioByName())->capture_default_str();
  soak->add_option("--minutes", o->minutes, "run length [min], >= 1")->capture_default_str();
  soak->add_option("--kill-every-s", o->kill_every_s, "seconds between kills: MIN MAX")->expected(2);
  soak->add_option("--seed", o->seed, "seed of the kill times and victims")->capture_default_str();
  soak->add_option("--out", o->out, "run directory (default runs/soak-<pid>)");
  soak->add_option("--set", o->overrides, "override a scenario key: key.path=value");
  soak->callback([o, &exit_code] { exit_code = runSoak(*o); });
  return soak;
}

}  // namespace flatsat::tools
