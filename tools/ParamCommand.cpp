// SPDX-License-Identifier: Apache-2.0
#include "tools/ParamCommand.hpp"

#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>

#include <nlohmann/json.hpp>

#include "bus/Endpoints.hpp"
#include "bus/NearestName.hpp"
#include "tools/CmdCommand.hpp"
#include "tools/ReportErrors.hpp"
#include "tools/ToolBus.hpp"

namespace flatsat::tools {
namespace {

struct ParamOptions {
  std::string component, key;
  double value = 0.0;
  bool json = false;
  double timeout_s = 15.0;  // set: for the acknowledgement
  int domain = -1;
};

struct Announced {
  std::uint64_t step = 0;
  std::vector<std::pair<std::string, double>> values;  // in the component's order
};

/// The components' last announcements (transient local: they come as their
/// writers match). Waits for discovery (kDiscoverySeconds) unless `only` came
/// first, or every live writer of the topic has been heard from.
std::map<std::string, Announced> announcements(ToolBus& tool_bus, const std::string& only) {
  std::mutex mutex;
  std::map<std::string, Announced> heard;
  bus::ReaderOf<bus::topics::kParamState> reader(
      tool_bus.bus(), bus::topics::kParamState, [&](const msg::ParamState& state, const Arrival&) {
        Announced a{state.header().step(), {}};
        for (const auto& v : state.values()) {
          if (const auto key = bus::text(v.key()); !key.empty()) a.values.emplace_back(key, v.value());
        }
        std::lock_guard lock(mutex);
        heard[bus::text(state.header().source())] = std::move(a);
      });
  const auto start = Clock::now();
  auto changed = start;  // when the count of writers or of announcements last moved
  std::pair<std::size_t, std::size_t> counts{0, 0};
  while (Clock::now() - start < std::chrono::duration<double>(kDiscoverySeconds)) {
    {
      std::lock_guard lock(mutex);
      if (!only.empty() && heard.count(only)) break;
      std::size_t writers = 0;
      for (const auto& w : tool_bus.writers()) writers += w.alive && w.topic == bus::topics::kParamState.name ? 1 : 0;
      const auto now = Clock::now();
      if (std::pair{writers, heard.size()} != counts) {
        counts = {writers, heard.size()};
        changed = now;
      }
      // Writers are discovered 0..3 s after a tool joins, one by one on a busy
      // machine: every writer heard is a full count only after a second in
      // which neither count moved.
      if (only.empty() && !heard.empty() && heard.size() >= writers && now - start > std::chrono::seconds(2) &&
          now - changed > std::chrono::seconds(1)) {
        break;
      }
    }
    if (!sleepUnlessInterrupted(0.05)) break;
  }
  std::lock_guard lock(mutex);
  return heard;
}

std::vector<std::string> namesOf(const std::map<std::string, Announced>& heard) {
  std::vector<std::string> names;
  for (const auto& [name, a] : heard) names.push_back(name);
  return names;
}

/// exit 1 and why when `component` did not announce; nullptr then.
const Announced* find(const std::map<std::string, Announced>& heard, const std::string& component,
                      const ToolBus& tool_bus) {
  if (const auto it = heard.find(component); it != heard.end()) return &it->second;
  std::string listed;
  for (const auto& name : namesOf(heard)) listed += (listed.empty() ? "" : ", ") + name;
  std::cerr << "error: no component '" << component << "' announced settable parameters on domain "
            << tool_bus.domain() << " within " << kDiscoverySeconds << " s"
            << bus::didYouMean(component, namesOf(heard))
            << (listed.empty() ? "; none did (is a rig running?)" : "; those that did: " + listed) << "\n";
  return nullptr;
}

int list(const ParamOptions& o) {
  ToolBus tool_bus("param", o.domain);
  const auto heard = announcements(tool_bus, o.component);
  std::map<std::string, Announced> shown;
  if (o.component.empty()) {
    shown = heard;
  } else if (const Announced* one = find(heard, o.component, tool_bus)) {
    shown[o.component] = *one;
  } else {
    return 1;
  }
  if (o.json) {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    for (const auto& [name, a] : shown) {
      nlohmann::ordered_json values = nlohmann::ordered_json::object();
      for (const auto& [key, value] : a.values) values[key] = value;
      out[name] = {{"since_step", a.step}, {"values", values}};
    }
    std::cout << out.dump(2) << "\n";
    return shown.empty() ? 1 : 0;
  }
  if (shown.empty()) {
    std::cerr << "error: no component announced settable parameters on domain " << tool_bus.domain() << " within "
              << kDiscoverySeconds << " s (is a rig running?)\n";
    return 1;
  }
  std::printf("%-22s %-22s %14s  %s\n", "COMPONENT", "KEY", "VALUE", "SINCE STEP");
  for (const auto& [name, a] : shown) {
    for (const auto& [key, value] : a.values) {
      std::printf("%-22s %-22s %14.6g  %llu\n", name.c_str(), key.c_str(), value,
                  static_cast<unsigned long long>(a.step));
    }
  }
  return 0;
}

int get(const ParamOptions& o) {
  ToolBus tool_bus("param", o.domain);
  const auto heard = announcements(tool_bus, o.component);
  const Announced* a = find(heard, o.component, tool_bus);
  if (a == nullptr) return 1;
  std::vector<std::string> keys;
  for (const auto& [key, value] : a->values) {
    if (key == o.key) {
      std::printf("%.17g\n", value);
      return 0;
    }
    keys.push_back(key);
  }
  std::string listed;
  for (const auto& key : keys) listed += (listed.empty() ? "" : ", ") + key;
  std::cerr << "error: " << o.component << " has no settable parameter '" << o.key << "'"
            << bus::didYouMean(o.key, keys) << "; it has " << listed << "\n";
  return 2;
}

}  // namespace

CLI::App* addParamCommand(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ParamOptions>();
  auto* param = app.add_subcommand("param", "list, get or set the parameters components let an operator set while they run");
  param->require_subcommand(1);

  auto* list_cmd = param->add_subcommand("list", "every settable parameter and its value now, by component");
  list_cmd->add_option("component", o->component, "only this component");
  list_cmd->add_flag("--json", o->json, "JSON: {component: {since_step, values: {key: value}}}");
  addDomainOption(*list_cmd, o->domain);
  list_cmd->callback([o, &exit_code] { runReportingErrors(exit_code, [&] { return list(*o); }); });

  auto* get_cmd = param->add_subcommand("get", "one parameter's value now (a number alone: for scripts)");
  get_cmd->add_option("component", o->component, "component: attitude_controller")->required();
  get_cmd->add_option("key", o->key, "key as in the scenario: kp_Nm_per_rad, ...")->required();
  addDomainOption(*get_cmd, o->domain);
  get_cmd->callback([o, &exit_code] { runReportingErrors(exit_code, [&] { return get(*o); }); });

  auto* set_cmd = param->add_subcommand("set", "change one while it runs (as flatsat cmd param): waits for the acknowledgement");
  set_cmd->add_option("component", o->component, "component: attitude_controller")->required();
  set_cmd->add_option("key", o->key, "key as in the scenario: kp_Nm_per_rad, ...")->required();
  set_cmd->add_option("value", o->value, "new value, in the unit the key names")->required();
  set_cmd->add_option("--timeout", o->timeout_s, "seconds to wait for the acknowledgement")->capture_default_str();
  addDomainOption(*set_cmd, o->domain);
  set_cmd->callback([o, &exit_code] {
    runReportingErrors(exit_code, [&] { return sendParamCommand(o->component, o->key, o->value, o->timeout_s, o->domain); });
  });
  param->footer(
      "Components announce their settable parameters on flatsat/param_state at their first step\n"
      "and after each change they accepted; list and get read those (about 4 s: discovery).\n"
      "set exits 0 accepted, 3 refused (the reason is printed), 1 no acknowledgement in time.");
  return param;
}

}  // namespace flatsat::tools
