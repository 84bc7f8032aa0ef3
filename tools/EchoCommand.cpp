// SPDX-License-Identifier: Apache-2.0
#include "tools/EchoCommand.hpp"

#include <cstdio>
#include <iostream>
#include <memory>
#include <mutex>

#include "tools/ToolBus.hpp"

namespace flatsat::tools {

namespace {

struct EchoOptions {
  std::string topic;
  bool json = false;
  bool jsonl = false;  ///< one compact JSON document per line
  std::string field;   ///< only this part of each sample ("" all)
  std::uint64_t count = 0;  ///< 0: until interrupted
  double timeout_s = 0.0;   ///< 0: none
  int domain = -1;
};

void appendValue(std::string& out, const nlohmann::ordered_json& value) {
  if (value.is_number_float()) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", value.get<double>());
    out += buffer;
  } else if (value.is_array()) {
    out += '[';
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (i > 0) out += ", ";
      appendValue(out, value[i]);
    }
    out += ']';
  } else {
    out += value.dump();
  }
}

/// `header.step=12 header.source="gyro" w_body_rad_s=[1e-05, 2e-05, 0]`:
/// nested structs by dotted names, doubles to 6 significant digits.
void appendFields(std::string& out, const nlohmann::ordered_json& object,
                  const std::string& prefix) {
  for (const auto& [key, value] : object.items()) {
    if (value.is_object()) {
      appendFields(out, value, prefix + key + ".");
      continue;
    }
    if (!out.empty()) out += ' ';
    out += prefix + key + "=";
    appendValue(out, value);
  }
}

/// Every path --field takes for a sample of `Def`, for the error that names them.
template <class Def>
std::string fieldPaths() {
  std::vector<std::pair<std::string, const nlohmann::ordered_json*>> leaves;
  const auto blank = msg::toJson(typename Def::Type{});
  flattenJson(blank, "", leaves);
  std::string paths;
  for (const auto& [path, leaf] : leaves) paths += (paths.empty() ? "" : ", ") + path;
  return paths;
}

std::string formatted(const nlohmann::ordered_json& value, const EchoOptions& o) {
  if (o.json) return value.dump(2);
  if (o.jsonl) return value.dump();
  std::string text;
  if (value.is_object()) {
    appendFields(text, value, "");
  } else {
    text = o.field + "=";
    appendValue(text, value);
  }
  return text;
}

template <class Def>
int echo(const Def& def, const EchoOptions& o) {
  if (!o.field.empty() && fieldOf(msg::toJson(typename Def::Type{}), o.field) == nullptr) {
    std::cerr << "error: " << def.name << " has no field '" << o.field << "'; its fields: " << fieldPaths<Def>()
              << " (a whole struct or array by its name, an element as name[i])\n";
    return 2;
  }
  ToolBus tool_bus("echo", o.domain);
  std::mutex mutex;
  std::uint64_t printed = 0;
  bus::Reader<Def> reader(tool_bus.bus(), def, [&](const typename Def::Type& sample, const Arrival&) {
    const auto json = msg::toJson(sample);
    const auto* part = o.field.empty() ? &json : fieldOf(json, o.field);
    if (part == nullptr) return;  // a bounded sequence shorter than the index asked for
    const std::string text = formatted(*part, o);
    std::lock_guard lock(mutex);
    if (o.count > 0 && printed >= o.count) return;
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fputc('\n', stdout);
    std::fflush(stdout);
    ++printed;
  });
  std::cerr << "flatsat echo: " << def.name << " on domain " << tool_bus.domain() << "\n";
  const auto deadline = Clock::now() + std::chrono::duration<double>(o.timeout_s);
  for (;;) {
    {
      std::lock_guard lock(mutex);
      if (o.count > 0 && printed >= o.count) return 0;
    }
    if (!sleepUnlessInterrupted(0.02)) return 0;
    if (o.timeout_s > 0 && Clock::now() > deadline) {
      std::lock_guard lock(mutex);
      std::cerr << "flatsat echo: " << printed << " of " << o.count << " samples on " << def.name
                << " within " << o.timeout_s << " s\n";
      return 1;
    }
  }
}

}  // namespace

CLI::App* addEchoCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<EchoOptions>();
  auto* cmd = app.add_subcommand("echo", "print a topic's samples as they arrive");
  cmd->add_option("topic", options->topic, "topic name: flatsat/truth, or just truth")->required();
  auto* json = cmd->add_flag("--json", options->json, "pretty JSON (full precision) instead of one line each");
  cmd->add_flag("--jsonl", options->jsonl, "one compact JSON document per line (full precision; for jq and scripts)")
      ->excludes(json);
  cmd->add_option("--field", options->field,
                  "print only this part of each sample: header.step, w_body_rad_s, w_body_rad_s[2]");
  cmd->add_option("-n,--count", options->count, "exit after N samples (default: until Ctrl-C)");
  cmd->add_option("--timeout", options->timeout_s,
                  "give up after S seconds [s], exit 1 (default: wait forever)")
      ->check(CLI::NonNegativeNumber);
  addDomainOption(*cmd, options->domain);
  cmd->footer(
      "Stepped topics are shown from the moment echo joins; health and commands also\n"
      "show each producer's latest sample from before. Arrays of chars are text,\n"
      "enums their names.");
  cmd->callback([options, &exit_code] {
    exit_code = runForTopic(options->topic, [&](const auto& def) { return echo(def, *options); });
  });
  return cmd;
}

}  // namespace flatsat::tools
