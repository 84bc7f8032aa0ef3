// SPDX-License-Identifier: Apache-2.0
#include "tools/TopicInfo.hpp"

#include <iostream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bus/Qos.hpp"
#include "tools/ReportErrors.hpp"
#include "tools/ToolBus.hpp"

namespace flatsat::tools {

namespace {

namespace dds = eprosima::fastdds::dds;

struct TopicInfoOptions {
  std::string topic;
  bool json = false;
  int domain = -1;
};

const char* presetName(bus::QosKind kind) {
  switch (kind) {
    case bus::QosKind::kStepped: return "stepped";
    case bus::QosKind::kProtocol: return "protocol";
    case bus::QosKind::kState: return "state";
    case bus::QosKind::kCommand: return "command";
  }
  return "?";
}

std::string seconds(const eprosima::fastrtps::Duration_t& d) {
  if (d == eprosima::fastrtps::c_TimeInfinite) return "infinite";
  std::ostringstream out;
  out << d.seconds + d.nanosec * 1e-9 << " s";
  return out.str();
}

template <class Qos>
nlohmann::ordered_json describe(const Qos& q) {
  const auto& h = q.history();
  const auto& l = q.liveliness();
  return {{"reliability", q.reliability().kind == dds::RELIABLE_RELIABILITY_QOS ? "reliable" : "best effort"},
          {"durability", q.durability().kind == dds::TRANSIENT_LOCAL_DURABILITY_QOS ? "transient local"
                         : q.durability().kind == dds::VOLATILE_DURABILITY_QOS      ? "volatile"
                                                                                    : "persistent"},
          {"history", h.kind == dds::KEEP_ALL_HISTORY_QOS ? std::string("keep all")
                                                          : "keep last " + std::to_string(h.depth)},
          {"ownership", q.ownership().kind == dds::EXCLUSIVE_OWNERSHIP_QOS ? "exclusive" : "shared"},
          {"liveliness", std::string(l.kind == dds::AUTOMATIC_LIVELINESS_QOS ? "automatic"
                                     : l.kind == dds::MANUAL_BY_TOPIC_LIVELINESS_QOS ? "manual by topic"
                                                                                     : "manual by participant") +
                             ", lease " + seconds(l.lease_duration)},
          {"deadline", seconds(q.deadline().period)}};
}

void print(const nlohmann::ordered_json& out) {
  const auto& producers = out["producers"];
  const auto& consumers = out["consumers"];
  std::cout << "topic:    " << out["topic"].get<std::string>() << "\ntype:     " << out["type"].get<std::string>()
            << "\nproducer: " << out["registry_producer"].get<std::string>() << " (registry)\nQoS:      "
            << out["qos_preset"].get<std::string>() << " preset\n";
  for (const char* side : {"writer_qos", "reader_qos"}) {
    std::cout << "  " << (side[0] == 'w' ? "writers" : "readers") << ":";
    for (const auto& [key, value] : out[side].items()) std::cout << " " << key << " " << value.get<std::string>() << ";";
    std::cout << "\n";
  }
  std::cout << "producers (" << producers.size() << "):\n";
  for (const auto& p : producers) {
    std::cout << "  " << p["participant"].get<std::string>() << "  " << p["writer_guid"].get<std::string>()
              << "  ownership strength " << p["ownership_strength"].get<int>() << "\n";
  }
  std::cout << "consumers (" << consumers.size() << "):\n";
  for (const auto& c : consumers) {
    std::cout << "  " << c["participant"].get<std::string>() << "  " << c["reader_guid"].get<std::string>() << "\n";
  }
}

template <class Def>
int showTopic(const Def& def, const TopicInfoOptions& o) {
  ToolBus tool_bus("topics-info", o.domain);
  if (!o.json) std::cerr << "flatsat topics info: " << def.name << " on domain " << tool_bus.domain() << "\n";
  if (!sleepUnlessInterrupted(kDiscoverySeconds)) return 130;
  const auto participant = [&](const Guid& guid) {
    const auto name = tool_bus.participantName(guid.guidPrefix);
    return name.empty() ? std::string("?") : name;
  };
  nlohmann::ordered_json out{{"topic", def.name},
                             {"type", typename Def::PubSubType().getName()},
                             {"registry_producer", def.producer.empty() ? "every component" : std::string(def.producer)},
                             {"qos_preset", presetName(def.qos)},
                             // Lockstep's tuning; paced rigs add a deadline and liveliness on stepped topics.
                             {"writer_qos", describe(bus::writerQos(def.qos))},
                             {"reader_qos", describe(bus::readerQos(def.qos))}};
  auto& producers = out["producers"] = nlohmann::ordered_json::array();
  for (const auto& w : tool_bus.writers()) {
    if (!w.alive || w.topic != def.name) continue;
    producers.push_back({{"participant", participant(w.guid)}, {"writer_guid", guidText(w.guid)},
                         {"ownership_strength", w.ownership_strength}});
  }
  auto& consumers = out["consumers"] = nlohmann::ordered_json::array();
  for (const auto& guid : tool_bus.readersOf(std::string(def.name))) {
    consumers.push_back({{"participant", participant(guid)}, {"reader_guid", guidText(guid)}});
  }
  if (o.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    print(out);
  }
  return 0;
}

}  // namespace

void addTopicInfoCommand(CLI::App& topics, int& exit_code) {
  auto o = std::make_shared<TopicInfoOptions>();
  auto* cmd = topics.add_subcommand("info", "one topic: its type, QoS, producers and consumers");
  cmd->add_option("topic", o->topic, "topic name: flatsat/truth, or just truth")->required();
  cmd->add_flag("--json", o->json, "print JSON");
  addDomainOption(*cmd, o->domain);
  cmd->footer("Listens 4 s for discovery. The QoS is the preset's as a lockstep rig sets it; a paced\n"
              "rig adds a deadline and manual-by-topic liveliness on stepped topics.");
  cmd->callback([o, &exit_code] {
    exit_code = runForTopic(o->topic, [&](const auto& def) { return showTopic(def, *o); });
  });
}

}  // namespace flatsat::tools
