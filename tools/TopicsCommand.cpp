// SPDX-License-Identifier: Apache-2.0
#include "tools/ReportErrors.hpp"
#include "tools/TopicsCommand.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bus/Stamp.hpp"
#include "tools/ToolBus.hpp"
#include "tools/TopicInfo.hpp"

namespace flatsat::tools {

namespace {

struct TopicsOptions {
  double seconds = 2.0;
  int domain = -1;
  bool verbose = false;
  bool json = false;
  bool all = false;  ///< every registry topic, produced or not
};

/// Samples of one writer written after the reader subscribed.
struct Stream {
  std::uint64_t samples = 0;
  Clock::time_point first{}, last{};
};

/// What one topic's reader saw.
struct TopicStats {
  std::string name;
  std::string type;
  bool in_registry = true;
  std::map<Guid, Stream> live;  ///< by writer: each matched when discovery got to it
  std::set<Guid> writers;       ///< writers a sample came from (history included)

  std::uint64_t samples() const {
    std::uint64_t n = 0;
    for (const auto& [guid, stream] : live) n += stream.samples;
    return n;
  }
};

struct Producer {
  std::string name;
  Guid guid;
  std::int32_t ownership_strength = 0;
};

/// [Hz] the sum over the writers of 1 / mean interval of their samples: how
/// long discovery took to match each writer does not count.
double rateHz(const TopicStats& stats) {
  double rate = 0.0;
  for (const auto& [guid, stream] : stats.live) {
    const double span = std::chrono::duration<double>(stream.last - stream.first).count();
    if (stream.samples >= 2 && span > 0.0) rate += static_cast<double>(stream.samples - 1) / span;
  }
  return rate;
}

/// Listens until the whole rig had time to be discovered and every writer
/// that sent samples was measured for `seconds` since its first (at most
/// `seconds` longer than that).
void listen(double seconds, std::mutex& mutex, const std::map<std::string, TopicStats>& stats) {
  const auto start = Clock::now();
  const double settle = std::max(seconds, kDiscoverySeconds);
  while (sleepUnlessInterrupted(0.05)) {
    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start).count();
    if (elapsed >= settle + seconds) return;
    if (elapsed < settle) continue;
    std::lock_guard lock(mutex);
    const auto measured = [&](const auto& stream) {
      return std::chrono::duration<double>(now - stream.second.first).count() >= seconds;
    };
    if (std::all_of(stats.begin(), stats.end(), [&](const auto& entry) {
          return std::all_of(entry.second.live.begin(), entry.second.live.end(), measured);
        })) {
      return;
    }
  }
}

int runTopics(const TopicsOptions& o) {
  ToolBus tool_bus("topics", o.domain);
  std::mutex mutex;
  std::map<std::string, TopicStats> stats;   // by topic name
  std::map<GuidPrefix, std::string> sources;  // participant -> header.source it writes
  std::vector<std::shared_ptr<void>> readers;
  bus::forEachTopic([&](const auto& def) {
    using Def = std::remove_cvref_t<decltype(def)>;
    auto& entry = stats[std::string(def.name)];
    entry.name = def.name;
    entry.type = typename Def::PubSubType().getName();
    readers.push_back(std::make_shared<bus::Reader<Def>>(
        tool_bus.bus(), def, [&mutex, &entry, &sources](const typename Def::Type& sample, const Arrival& a) {
          std::lock_guard lock(mutex);
          entry.writers.insert(a.writer);
          // Every sample names its producer (Health's header.source names the component).
          const auto source = bus::text(sample.header().source());
          if (!source.empty()) sources[a.writer.guidPrefix] = source;
          if (a.historical) return;
          auto& stream = entry.live[a.writer];
          if (stream.samples++ == 0) stream.first = a.wall;
          stream.last = a.wall;
        }));
  });
  if (!o.json) {
    std::cerr << "flatsat topics: listening on domain " << tool_bus.domain() << "\n";
  }
  listen(o.seconds, mutex, stats);
  readers.clear();  // no callback runs past here

  const auto participants = tool_bus.participants();
  const auto nameOf = [&](const Guid& guid) {
    if (auto it = sources.find(guid.guidPrefix); it != sources.end()) return it->second;
    const auto name = tool_bus.participantName(guid.guidPrefix);
    return name.empty() ? guidText(guid) : name;
  };
  std::map<std::string, std::map<Guid, Producer>> producers;
  for (const auto& writer : tool_bus.writers()) {
    if (!writer.alive) continue;
    if (stats.count(writer.topic) == 0) {  // a topic the registry does not know
      auto& entry = stats[writer.topic];
      entry.name = writer.topic;
      entry.type = writer.type;
      entry.in_registry = false;
    }
    producers[writer.topic][writer.guid] = {nameOf(writer.guid), writer.guid,
                                            writer.ownership_strength};
  }
  for (const auto& [topic, entry] : stats) {
    for (const auto& guid : entry.writers) {
      producers[topic].try_emplace(guid, Producer{nameOf(guid), guid, 0});
    }
  }

  nlohmann::ordered_json out;
  out["domain"] = tool_bus.domain();
  out["seconds"] = o.seconds;
  auto& parts = out["participants"] = nlohmann::ordered_json::array();
  for (const auto& [prefix, info] : participants) {
    std::ostringstream text;
    text << prefix;
    parts.push_back({{"guid_prefix", text.str()}, {"name", info.name}, {"alive", info.alive}});
  }
  auto& topics = out["topics"] = nlohmann::ordered_json::array();
  for (const auto& [topic, entry] : stats) {
    if (!o.all && producers[topic].empty()) continue;  // nobody writes it on this domain
    nlohmann::ordered_json t{{"name", topic},
                             {"type", entry.type},
                             {"in_registry", entry.in_registry},
                             {"rate_hz", rateHz(entry)},
                             {"samples", entry.samples()}};
    auto& list = t["producers"] = nlohmann::ordered_json::array();
    for (const auto& [guid, p] : producers[topic]) {
      list.push_back({{"name", p.name},
                      {"writer_guid", guidText(guid)},
                      {"ownership_strength", p.ownership_strength}});
    }
    topics.push_back(t);
  }

  if (o.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf("%-28s %-36s %10s %8s  %s\n", "TOPIC", "TYPE", "RATE [Hz]", "SAMPLES",
                "PRODUCERS");
    for (const auto& t : topics) {
      std::set<std::string> names;
      for (const auto& p : t["producers"]) names.insert(p["name"].get<std::string>());
      std::string joined;
      for (const auto& n : names) joined += (joined.empty() ? "" : ", ") + n;
      char rate[32] = "-";
      if (t["rate_hz"].get<double>() > 0) std::snprintf(rate, sizeof rate, "%.1f", t["rate_hz"].get<double>());
      std::printf("%-28s %-36s %10s %8llu  %s%s\n", t["name"].get<std::string>().c_str(),
                  t["type"].get<std::string>().c_str(), rate,
                  static_cast<unsigned long long>(t["samples"].get<std::uint64_t>()),
                  joined.empty() ? "-" : joined.c_str(),
                  t["in_registry"].get<bool>() ? "" : "  (not in the registry)");
      if (!o.verbose) continue;
      for (const auto& p : t["producers"]) {
        std::printf("    writer %-40s %-24s ownership strength %d\n",
                    p["writer_guid"].get<std::string>().c_str(), p["name"].get<std::string>().c_str(),
                    p["ownership_strength"].get<int>());
      }
    }
    std::printf("%zu participants on domain %u:", participants.size(), tool_bus.domain());
    for (const auto& [prefix, info] : participants) {
      std::printf(" %s%s", info.name.c_str(), info.alive ? "" : " (gone)");
    }
    std::printf("\n");
  }
  if (participants.empty()) {
    std::cerr << "flatsat topics: no participant on domain " << tool_bus.domain() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

CLI::App* addTopicsCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<TopicsOptions>();
  auto* cmd = app.add_subcommand(
      "topics", "what is on the bus: each live topic's type, producers and measured rate");
  cmd->add_option("-s,--seconds", options->seconds,
                  "how long to measure each topic's rate [s] (default 2)")
      ->check(CLI::PositiveNumber);
  addDomainOption(*cmd, options->domain);
  cmd->add_flag("-v,--verbose", options->verbose,
                "list each writer: GUID, producer and ownership strength");
  cmd->add_flag("--json", options->json, "print JSON instead of a table");
  cmd->add_flag("--all", options->all, "every registry topic, also those nobody writes on this domain");
  cmd->footer(
      "Lists the topics a live writer announced or sent a sample of (--all: the whole registry).\n"
      "Producers are named by the header.source of their samples (Health for every\n"
      "component), else by their participant's name. RATE is 1 / mean interval of the\n"
      "samples written while listening, in wall time. Listens at least 4 s: the rig's\n"
      "components answer a new participant at their next discovery announcement.");
  addTopicInfoCommand(*cmd, exit_code);
  cmd->require_subcommand(0, 1);
  cmd->callback([cmd, options, &exit_code] {
    if (!cmd->get_subcommands().empty()) return;  // `topics info` ran
    runReportingErrors(exit_code, [&] { return runTopics(*options); });
  });
  return cmd;
}

}  // namespace flatsat::tools
