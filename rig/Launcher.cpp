// SPDX-License-Identifier: Apache-2.0
#include "rig/Launcher.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include <spdlog/spdlog.h>

#include "bus/Endpoints.hpp"
#include "bus/Shutdown.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"
#include "bus/NodeMain.hpp"
#include "bus/Security.hpp"
#include "components/Registry.hpp"
#include "rig/Progress.hpp"
#include "rig/Spawn.hpp"

namespace flatsat::rig {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Child {
  std::string name;
  pid_t pid = -1;
  bool running = true;
  std::string log;
  bool required = true;  // a stepped component: its death stops the rig
  bool restarted = false;  // started again mid-run: it takes its checkpoint back
  bool program = false;    // a scenario's program (not on the bus): its exit mid-run fails the run
};

/// A program's argv: "{run}" replaced by the run directory, a bare first word found
/// beside the flatsat tool when it is there (else posix_spawnp looks on PATH).
std::vector<std::string> programArgv(const bus::ProgramEntry& program, const std::string& run_dir,
                                     const std::string& bin_dir) {
  std::vector<std::string> argv;
  for (std::string word : program.command) {
    for (auto at = word.find("{run}"); at != std::string::npos; at = word.find("{run}", at + run_dir.size())) {
      word.replace(at, 5, run_dir);
    }
    argv.push_back(word);
  }
  if (argv.front().find('/') == std::string::npos && fs::exists(fs::path(bin_dir) / argv.front())) {
    argv.front() = (fs::path(bin_dir) / argv.front()).string();
  }
  return argv;
}

std::string tail(const std::string& path, std::size_t lines) {
  std::ifstream in(path);
  std::vector<std::string> all;
  for (std::string line; std::getline(in, line);) all.push_back(line);
  std::string out;
  for (std::size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) {
    out += "    " + all[i] + "\n";
  }
  return out;
}

void stopAll(std::vector<Child>& children) {
  for (auto& c : children) {
    if (c.running) kill(c.pid, SIGTERM);
  }
  const auto deadline = Clock::now() + std::chrono::seconds(5);
  for (auto& c : children) {
    while (c.running) {
      int status = 0;
      if (waitpid(c.pid, &status, WNOHANG) == c.pid) {
        c.running = false;
      } else if (Clock::now() > deadline) {
        kill(c.pid, SIGKILL);
        waitpid(c.pid, &status, 0);
        c.running = false;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    }
  }
}

/// [s] How long an external component may take to first report on the bus:
/// the dynamics server waits 60 s for it, and a container or a far host
/// needs a few seconds more to start.
constexpr double kExternalJoinTimeout = 90.0;

/// Follows the external components on the health topic: when each first shows
/// up, and whether each stepped one finished (STOPPED) or failed. A rig whose
/// every component is external (one container each) lasts until they finish.
class Externals {
 public:
  Externals(bus::Bus& bus, const bus::Scenario& scenario, Clock::time_point start)
      : start_(start),
        paced_(scenario.pacing == bus::Pacing::kPaced),
        waiting_(named(scenario, false)),
        unfinished_(named(scenario, true)),
        reader_(
            bus, bus::topics::kHealth, [this](const msg::Health& health) { receive(health); },
            [this](const std::string& source, bool alive) {
              if (!alive) lost(source);
            },
            {},
            // A health naming another participant than its writer's is not
            // that component's word (architecture, "Trust on the bus").
            bus::WriterTrust{{}, true, [](const std::string& guid, const std::string& participant, bool first, bool) {
              if (first) {
                spdlog::error("launcher: health from participant '{}' (writer {}) names another component; ignored",
                              participant, guid);
              }
            }}) {}

  /// Logs the joins and losses since the last call.
  void report() {
    std::lock_guard lock(mutex_);
    for (const auto& name : fresh_) {
      spdlog::info("external {} joined the bus {:.2f} s after launch", name, joined_[name]);
    }
    fresh_.clear();
    for (const auto& name : gone_) {
      spdlog::warn("external {} lost its liveliness ({} ms without a sign of life); the paced run goes on",
                   name, bus::kHealthLease.count());
    }
    gone_.clear();
  }
  std::map<std::string, double> joined() {
    std::lock_guard lock(mutex_);
    return joined_;
  }
  std::string missing() {
    std::lock_guard lock(mutex_);
    return waitingNames();
  }
  /// Stepped external components that have not reported STOPPED or FAILED.
  std::size_t running() {
    std::lock_guard lock(mutex_);
    return unfinished_.size();
  }
  /// Why the run cannot go on because of an external component; "" if it can.
  std::string failure() {
    std::lock_guard lock(mutex_);
    if (!failure_.empty() || waiting_.empty()) return failure_;
    if (std::chrono::duration<double>(Clock::now() - start_).count() > kExternalJoinTimeout) {
      return "external components did not join the bus within " +
             std::to_string(static_cast<int>(kExternalJoinTimeout)) + " s:" + waitingNames();
    }
    return "";
  }

 private:
  /// " a b c" for the components not seen yet; called with mutex_ held.
  std::string waitingNames() const {
    std::string names;
    for (const auto& name : waiting_) names += " " + name;
    return names;
  }

  static std::set<std::string> named(const bus::Scenario& scenario, bool stepped_only) {
    std::set<std::string> names;
    for (const auto& c : scenario.components) {
      if (!c.launched && (c.scheduled || !stepped_only)) names.insert(c.name);
    }
    return names;
  }

  void receive(const msg::Health& health) {
    const auto source = bus::text(health.header().source());
    std::lock_guard lock(mutex_);
    if (waiting_.erase(source) > 0) {
      joined_[source] = std::chrono::duration<double>(Clock::now() - start_).count();
      fresh_.push_back(source);
    }
    if (unfinished_.count(source) == 0) return;
    if (health.state() == msg::ComponentState::FAILED && failure_.empty()) {
      failure_ = "external component '" + source + "' failed: " + bus::text(health.message());
    }
    if (health.state() == msg::ComponentState::STOPPED || health.state() == msg::ComponentState::FAILED) {
      unfinished_.erase(source);
    }
  }

  /// An external component's process is gone: lockstep cannot go on without
  /// it; paced goes on and no longer waits for it to finish.
  void lost(const std::string& source) {
    std::lock_guard lock(mutex_);
    if (unfinished_.count(source) == 0) return;
    if (paced_) {
      unfinished_.erase(source);
      gone_.push_back(source);
    } else if (failure_.empty()) {
      failure_ = "external component '" + source + "' lost its liveliness (" +
                 std::to_string(bus::kHealthLease.count()) + " ms without a sign of life: its process is gone)";
    }
  }

  Clock::time_point start_;
  bool paced_;
  std::vector<std::string> gone_;  // paced: lost, not yet logged
  std::mutex mutex_;
  std::set<std::string> waiting_;     // not seen yet
  std::set<std::string> unfinished_;  // stepped, not STOPPED or FAILED yet
  std::map<std::string, double> joined_;
  std::vector<std::string> fresh_;
  std::string failure_;
  bus::ReaderOf<bus::topics::kHealth> reader_;  // last: it calls receive() from Fast DDS's thread
};

}  // namespace

LaunchResult launch(const bus::Scenario& scenario, const LaunchOptions& options) {
  const auto entered = Clock::now();  // startup includes the launcher's own participant
  LaunchResult result;
  const fs::path logs = fs::path(options.run_dir) / "logs";
  fs::create_directories(logs);
  bus::BusOptions bus_options{.domain_id = bus::domainFromEnvironment(scenario.domain_id),
                              .participant_name = "flatsat-launcher",
                              .tuning = bus::qosTuning(scenario, bus::kEmulatorStrength),
                              .identity = bus::kOperatorIdentity};
  bus::useNetwork(bus_options, bus::networkFromEnvironment());
  bus::Bus bus(bus_options);
  const bool paced = scenario.pacing == bus::Pacing::kPaced;
  Progress progress(bus, options.progress, paced, paced ? Progress::Follow::kGrants : Progress::Follow::kMasterHealth);

  const auto start = Clock::now();
  Externals externals(bus, scenario, start);
  // The time master's verdicts on the components, as they happen.
  bus::ReaderOf<bus::topics::kFaultEvent> component_events(bus, bus::topics::kFaultEvent, [](const msg::FaultEvent& e) {
    const std::string kind = bus::text(e.kind());
    if (kind != "lost" && kind != "late") return;
    const std::string component = bus::text(e.header().source());
    if (!e.active()) {
      spdlog::info("{} is {} again (step {})", component, kind == "lost" ? "alive" : "on time", e.header().step());
    } else if (kind == "lost") {
      spdlog::warn("{} lost its liveliness at step {}: its process is gone", component, e.header().step());
    } else {
      spdlog::warn("{} is late at step {}: no health for at least {} ms", component, e.header().step(),
                   bus::kHealthLate.count());
    }
  });
  std::vector<Child> children;
  std::vector<const bus::ComponentEntry*> late;  // bridges that start after a delay
  // --restart: the time master owns simulated time and cannot come back mid-run.
  const bool may_restart = options.restart && scenario.pacing == bus::Pacing::kPaced;
  // What only the launcher knows: it starts every process of the rig on this
  // host, none under a prefix, all at the start (a bridge that joined later
  // could have its first samples missed by a best-effort reader after the
  // step 0 resend). A writer nobody declared, joining from another host, is
  // not provided for (declare it: `role: external`). Each child weighs the
  // rest itself (lockstep, shared memory, no DDS Security: processBusOptions).
  const bool shared_memory_rig =
      options.prefixes.empty() &&
      std::all_of(scenario.components.begin(), scenario.components.end(),
                  [](const auto& c) { return c.launched && c.start_after_s == 0.0; });
  const auto spawn = [&](Child& child) {
    const auto* kind = findComponentKind(child.name);
    std::vector<std::string> argv;
    if (auto it = options.prefixes.find(child.name); it != options.prefixes.end()) {
      argv = it->second;
    }
    argv.insert(argv.end(), {(fs::path(options.bin_dir) / kind->executable).string(), "--scenario",
                             options.scenario_file, "--name", child.name, "--out",
                             options.run_dir, "--log", options.log_level});
    if (may_restart) argv.push_back(child.restarted ? "--restarted" : "--checkpoint");
    if (shared_memory_rig) argv.push_back("--shared-memory-rig");
    child.pid = spawnLogged(argv, child.log);
    child.running = true;
    spdlog::debug("started {} (pid {})", child.name, child.pid);
  };
  const auto startChild = [&](const bus::ComponentEntry& component) {
    Child child{component.name, -1, true, (logs / (component.name + ".log")).string(),
                component.scheduled};
    spawn(child);
    children.push_back(child);
  };
  bus::WriterOf<bus::topics::kFaultEvent> restart_events(bus, bus::topics::kFaultEvent);
  const auto restartChild = [&](Child& c, int status) {
    const int n = ++result.restarts[c.name];
    spdlog::warn("{} died ({}); starting it again ({} of at most {})", c.name, describeExit(status), n,
                 options.max_restarts);
    msg::FaultEvent event;
    const std::uint64_t step = progress.steps();
    bus::stamp(event.header(), {step, static_cast<std::int64_t>(step) * std::llround(scenario.step_s * 1e9), 0},
               c.name);
    bus::setText(event.kind(), "restarted");
    event.channel(-1);
    event.magnitude(n);
    event.active(true);
    restart_events.write(event);
    c.log = (logs / (c.name + ".restart-" + std::to_string(n) + ".log")).string();
    c.restarted = true;
    spawn(c);
  };
  for (const auto& component : scenario.components) {
    if (!component.launched) {
      spdlog::info("{} is external: waiting for it on the bus", component.name);
    } else if (component.start_after_s > 0.0) {
      late.push_back(&component);
    } else {
      startChild(component);
    }
  }
  for (const auto& program : scenario.programs) {
    Child child{program.name, -1, true, (logs / (program.name + ".log")).string(), false};
    child.program = true;
    try {
      child.pid = spawnLogged(programArgv(program, options.run_dir, options.bin_dir), child.log);
    } catch (const std::exception& e) {
      // The rig started already: it is stopped below, not left running.
      result.failure = "program '" + program.name + "' could not be started: " + e.what();
      break;
    }
    spdlog::info("started program {} (pid {})", program.name, child.pid);
    children.push_back(child);
  }
  result.processes = children.size() + late.size();
  for (const auto& c : scenario.components) result.processes += !c.launched && c.scheduled;

  auto next_print = Clock::now();
  // The run lasts as long as the stepped components; bridges are stopped after.
  const auto steppedRunning = [&] {
    std::size_t n = 0;
    for (const auto& c : children) n += c.running && c.required;
    return n;
  };
  const auto rigRunning = [&] { return steppedRunning() > 0 || externals.running() > 0; };
  const auto rigStopping = [&] {  // the time master is gone: the run is over
    return std::none_of(children.begin(), children.end(),
                        [](const Child& c) { return c.name == "dynamics_server" && c.running; });
  };
  while (result.failure.empty() && rigRunning()) {
    for (auto it = late.begin(); it != late.end();) {
      if (Clock::now() - start >= std::chrono::duration<double>((*it)->start_after_s)) {
        spdlog::info("starting bridge {} ({} s after launch)", (*it)->name, (*it)->start_after_s);
        startChild(**it);
        it = late.erase(it);
      } else {
        ++it;
      }
    }
    // Of the components found dead in one poll, the one a signal killed is
    // the cause; the others exited reacting to it (e.g. the time master
    // failing the run when the killed one's liveliness lapsed).
    std::string signalled_failure;
    std::string exited_failure;
    for (auto& c : children) {
      int status = 0;
      if (!c.running || waitpid(c.pid, &status, WNOHANG) != c.pid) continue;
      c.running = false;
      if (c.program && !rigStopping()) {
        // Not on the bus, so no emulator stands behind it: the rig has lost what it did.
        if (exited_failure.empty()) {
          exited_failure = "program '" + c.name + "' exited (" + describeExit(status) + ") before the run ended; last lines of " +
                           c.log + ":\n" + tail(c.log, 8);
        }
        continue;
      }
      if (c.program) {
        spdlog::info("program {} exited ({}) as the run ended", c.name, describeExit(status));
        continue;
      }
      if (!c.required) {
        // A bridge that dies is the swap-in case: readers fall back to the emulator.
        spdlog::warn("bridge {} exited ({}); the emulator takes over", c.name, describeExit(status));
        continue;
      }
      const bool died = !(WIFEXITED(status) && WEXITSTATUS(status) == 0);
      if (died && may_restart && c.name != "dynamics_server" && !rigStopping() &&
          result.restarts[c.name] < options.max_restarts) {
        restartChild(c, status);
        continue;
      }
      if (!died) continue;
      std::string& failure = WIFSIGNALED(status) ? signalled_failure : exited_failure;
      if (failure.empty()) {
        failure = "component '" + c.name + "' died (" + describeExit(status) + "); last lines of " + c.log +
                  ":\n" + tail(c.log, 8);
      }
    }
    if (result.failure.empty()) result.failure = !signalled_failure.empty() ? signalled_failure : exited_failure;
    if (result.failure.empty()) result.failure = externals.failure();
    if (!result.failure.empty() || bus::shutdownRequested()) break;
    externals.report();
    progress.poll();
    if (Clock::now() >= next_print) {
      progress.print(false);
      next_print += std::chrono::milliseconds(500);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (rigRunning() && result.failure.empty()) {
    result.failure = "interrupted; stopping every component";
  }
  stopAll(children);
  externals.report();
  if (const auto missing = externals.missing(); !result.failure.empty() && !missing.empty()) {
    result.failure += "\nexternal components that never joined the bus:" + missing;
  }
  progress.print(true);
  result.launch_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  result.step_seconds = progress.stepSeconds();
  result.startup_seconds = progress.startupSeconds(entered);
  result.steps = progress.steps();
  result.tick_jitter = progress.tickJitter();
  result.external_joined_s = externals.joined();
  result.ok = result.failure.empty();
  return result;
}

}  // namespace flatsat::rig
