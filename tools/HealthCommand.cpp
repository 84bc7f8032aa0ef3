// SPDX-License-Identifier: Apache-2.0
#include "tools/ReportErrors.hpp"
#include "tools/HealthCommand.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "bus/Stamp.hpp"
#include "tools/HealthTable.hpp"
#include "tools/ToolBus.hpp"

namespace flatsat::tools {

namespace {

struct HealthOptions {
  bool once = false;
  double wait_s = 8.0;
  double every_s = 1.0;  // [s] watch: refresh period, in [0.1, 60]
  bool json = false;
  int domain = -1;
  std::string component;  // --component: that one only, its state as the exit code
};

void printTable(const nlohmann::ordered_json& rows, std::uint32_t domain) {
  std::printf("%-22s %-14s %10s %6s %9s %6s %9s %8s %8s %8s  %s\n", "COMPONENT", "STATE", "STEPS", "LAG",
              "OVERRUNS", "STALE", "DEADLINES", "DROPPED", "REFUSED", "AGE [s]", "MESSAGE");
  for (const auto& r : rows) {
    std::string state = r["state"].is_string() ? r["state"].get<std::string>() : r["state"].dump();
    if (!r["alive"].get<bool>()) state += " (gone)";
    if (r["late"].get<bool>()) state += " (late)";
    std::printf("%-22s %-14s %10llu %6llu %9llu %6llu %9llu %8llu %8llu %8.1f  %s\n",
                r["component"].get<std::string>().c_str(), state.c_str(),
                static_cast<unsigned long long>(r["steps_done"].get<std::uint64_t>()),
                static_cast<unsigned long long>(r["lag_steps"].get<std::uint64_t>()),
                static_cast<unsigned long long>(r["overruns"].get<std::uint64_t>()),
                static_cast<unsigned long long>(r["stale_inputs"].get<std::uint64_t>()),
                static_cast<unsigned long long>(r["deadlines_missed"].get<std::uint64_t>()),
                static_cast<unsigned long long>(r["samples_dropped"].get<std::uint64_t>()),
                static_cast<unsigned long long>(r["commands_refused"].get<std::uint64_t>()),
                r["age_s"].get<double>(), r["message"].get<std::string>().c_str());
  }
  std::printf("%zu components on domain %u\n", rows.size(), domain);
  std::fflush(stdout);
}

/// One component's health as a probe (container health checks): 0 when it
/// reported within --wait and is neither FAILED nor gone, else 1.
int probe(const HealthOptions& o, const ToolBus& tool_bus, std::mutex& mutex,
          const std::map<std::string, HealthEntry>& entries) {
  const auto start = Clock::now();
  const auto reported = [&] {
    std::lock_guard lock(mutex);
    return entries.count(o.component) > 0;
  };
  while (!reported() && std::chrono::duration<double>(Clock::now() - start).count() < o.wait_s) {
    if (!sleepUnlessInterrupted(0.1)) break;
  }
  nlohmann::ordered_json rows;
  {
    std::lock_guard lock(mutex);
    std::map<std::string, HealthEntry> one;
    if (auto it = entries.find(o.component); it != entries.end()) one.insert(*it);
    rows = healthTable(one, tool_bus);
  }
  if (o.json) std::cout << rows.dump(2) << "\n";
  else printTable(rows, tool_bus.domain());
  if (rows.empty()) {
    std::cerr << "flatsat health: " << o.component << " did not report within " << o.wait_s << " s\n";
    return 1;
  }
  const auto& row = rows.front();
  return row["alive"].get<bool>() && row["state"] != "FAILED" ? 0 : 1;
}

int health(const HealthOptions& o) {
  ToolBus tool_bus("health", o.domain);
  std::mutex mutex;
  std::map<std::string, HealthEntry> entries;  // by component (header.source)
  HealthWatcher watcher(tool_bus, mutex, entries);
  const auto snapshot = [&] {
    std::lock_guard lock(mutex);
    return healthTable(entries, tool_bus);
  };

  if (!o.component.empty()) return probe(o, tool_bus, mutex, entries);
  // Each component's health writer keeps its last sample for late joiners:
  // the first table waits until every discovered health writer delivered,
  // after the time discovery needs to find every component (at most --wait),
  // so that it is never a part of the rig.
  const auto start = Clock::now();
  if (!o.once && !o.json) std::cerr << "flatsat health: discovering the rig on domain " << tool_bus.domain() << "\n";
  for (;;) {
    if (!sleepUnlessInterrupted(0.1)) return 0;
    const double waited = std::chrono::duration<double>(Clock::now() - start).count();
    if (waited >= o.wait_s) break;
    if (waited < std::min(kDiscoverySeconds, o.wait_s)) continue;
    std::lock_guard lock(mutex);
    bool missing = false;
    for (const auto& w : tool_bus.writers()) {
      if (!w.alive || w.topic != bus::topics::kHealth.name) continue;
      missing |= std::none_of(entries.begin(), entries.end(),
                              [&](const auto& e) { return e.second.writer == w.guid; });
    }
    if (!missing && !entries.empty()) break;
  }
  if (o.once) {
    const auto rows = snapshot();
    if (o.json) {
      std::cout << rows.dump(2) << "\n";
    } else {
      printTable(rows, tool_bus.domain());
    }
    if (rows.empty()) {
      std::cerr << "flatsat health: no component reported on domain " << tool_bus.domain() << "\n";
      return 1;
    }
    return 0;
  }

  const bool tty = ::isatty(STDOUT_FILENO) != 0;
  for (bool first = true; first || sleepUnlessInterrupted(o.every_s); first = false) {
    const auto rows = snapshot();
    if (o.json) {
      std::cout << rows.dump() << "\n" << std::flush;
      continue;
    }
    if (tty) std::printf("\033[H\033[2J");  // redraw in place
    printTable(rows, tool_bus.domain());
    if (!tty) std::printf("\n");
  }
  return 0;
}

}  // namespace

CLI::App* addHealthCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<HealthOptions>();
  auto* cmd = app.add_subcommand(
      "health", "a live table of the rig's components: state, steps, message, age");
  cmd->add_flag("--once", options->once, "print one table and exit (tests, CI)");
  cmd->add_option("--wait", options->wait_s,
                  "before the first table, wait at most S seconds for every component's health [s] (default 8; "
                  "discovery alone takes up to 4)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--component", options->component,
                  "only this component, once: exit 0 when it reported within --wait and is "
                  "neither FAILED nor gone (a container health check)");
  cmd->add_flag("--json", options->json, "JSON rows instead of a table (one line per refresh)");
  cmd->add_option("--every", options->every_s, "watch: refresh every S seconds [s] (default 1)")
      ->check(CLI::Range(0.1, 60.0));
  addDomainOption(*cmd, options->domain);
  cmd->footer(
      "Refreshed every second until Ctrl-C; the first table comes once every component\n"
      "discovery found has reported (at most --wait). LAG is how many granted steps a component had\n"
      "not yet handled when it stamped its last health (the time master: 0); AGE is the time since the component\n"
      "stamped its last health (wall clock; a running component reports every second);\n"
      "OVERRUNS and STALE count the paced steps it skipped or took with an old input.\n"
      "(gone): the component's participant left the bus.");
  cmd->callback([options, &exit_code] { runReportingErrors(exit_code, [&] { return health(*options); }); });
  return cmd;
}

}  // namespace flatsat::tools
