// SPDX-License-Identifier: Apache-2.0
#include "bus/InstallPaths.hpp"
#include "tools/GrantsCommand.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "bus/LocalHub.hpp"
#include "bus/NodeMain.hpp"
#include "bus/Security.hpp"
#include "bus/Topics.hpp"
#include "components/Registry.hpp"
#include "tools/ReportErrors.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::tools {

namespace {

namespace fs = std::filesystem;
using TopicSet = std::set<std::string, std::less<>>;

struct TopicInfo {
  std::string name;
  std::string producer;
  bus::QosKind qos;
};

std::vector<TopicInfo> registryTopics() {
  std::vector<TopicInfo> topics;
  bus::forEachTopic([&](const auto& def) {
    topics.push_back({std::string(def.name), std::string(def.producer), def.qos});
  });
  return topics;
}

/// The scenarios shipped with flatsat (the first scenario folder holding any), default.yaml first.
std::vector<bus::Scenario> shippedScenarios(std::string& where) {
  for (const auto& dir : bus::scenarioDirs()) {
    std::vector<fs::path> files = bus::scenarioFilesIn(dir);
    std::stable_partition(files.begin(), files.end(), [](const fs::path& f) { return f.filename() == "default.yaml"; });
    std::vector<bus::Scenario> scenarios;
    for (const auto& file : files) {
      try {
        scenarios.push_back(bus::loadScenario(file.string()));
      } catch (const std::exception&) {
        // a broken scenario is `flatsat check`'s business; the others still list the kinds
      }
    }
    if (!scenarios.empty()) {
      where = dir.string();
      return scenarios;
    }
  }
  where = bus::listOfDirs(bus::scenarioDirs());
  return {};
}

/// A scratch run directory (the recorder opens its recording there), removed after.
struct ScratchDir {
  fs::path path = fs::temp_directory_path() / ("flatsat-grants-" + std::to_string(::getpid()));
  ScratchDir() { fs::create_directories(path); }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
};

/// Only warnings while nodes are built for a look at their writers.
struct QuietLog {
  spdlog::level::level_enum previous = spdlog::default_logger()->level();
  QuietLog() { spdlog::default_logger()->set_level(spdlog::level::warn); }
  ~QuietLog() { spdlog::default_logger()->set_level(previous); }
  QuietLog(const QuietLog&) = delete;
  QuietLog& operator=(const QuietLog&) = delete;
};

/// The registry topics a component kind's code writes and reads.
struct Endpoints {
  TopicSet written, read;
};

/// The endpoints of each composable component kind: its node, built (not run)
/// on an in-process bus from every shipped scenario that lists it (what a
/// node reads depends on its parameters), and the writers and readers it made
/// (every node makes them as it is built). Throws std::runtime_error when a
/// kind cannot be built from any of them.
std::map<std::string, Endpoints> endpointsOfComponents() {
  std::string where;
  const auto scenarios = shippedScenarios(where);
  const ScratchDir scratch;
  const QuietLog quiet;
  std::map<std::string, Endpoints> endpoints;
  for (const auto& kind : componentKinds()) {
    if (!kind.make) continue;  // process-only (a bridge, a device stand-in): see securityGrants()
    std::string why = "no scenario in " + where + " lists it";
    for (const auto& scenario : scenarios) {
      if (!scenario.hasComponent(kind.name)) continue;
      try {
        bus::LocalHub hub;
        bus::BusOptions options;
        options.participant_name = kind.name;
        bus::Bus bus(options, hub);
        const auto node = kind.make(bus, bus::nodeOptions(scenario, kind.name), scenario, vehicle::vehicleOf(scenario),
                                    {scenario.file, kind.name, scratch.path.string()});
        auto& seen = endpoints[kind.name];
        bus::forEachTopic([&](const auto& def) {
          if (hub.channel(def).writers() > 0) seen.written.emplace(def.name);
          if (hub.channel(def).readers() > 0) seen.read.emplace(def.name);
        });
      } catch (const std::exception& e) {
        why = scenario.file + ": " + e.what();
      }
    }
    if (!endpoints.contains(kind.name)) {
      throw std::runtime_error("cannot see which topics component '" + kind.name + "' writes: " + why);
    }
  }
  return endpoints;
}

}  // namespace

std::vector<std::string> grantIdentities() {
  std::vector<std::string> identities;
  for (const auto& kind : componentKinds()) identities.push_back(kind.name);
  identities.emplace_back(bus::kOperatorIdentity);
  identities.emplace_back(kReplayIdentity);
  return identities;
}

std::vector<Grant> securityGrants(const std::vector<std::string>& requested) {
  const auto identities = requested.empty() ? grantIdentities() : requested;
  for (const auto& id : identities) {
    if (id == bus::kOperatorIdentity || id == kReplayIdentity || findComponentKind(id) != nullptr) continue;
    std::string known;
    for (const auto& each : grantIdentities()) known += " " + each;
    throw std::invalid_argument("'" + id + "': no component kind or tool identity of that name (known:" + known +
                                ")");
  }
  const auto topics = registryTopics();
  const auto endpoints = endpointsOfComponents();
  // The registry names one producer per stepped topic: a component's code
  // writing another's topic is a registry out of date, not a grant to widen.
  TopicSet written_by_any;
  for (const auto& [kind, seen] : endpoints) {
    for (const auto& topic : topics) {
      if (!seen.written.contains(topic.name)) continue;
      written_by_any.insert(topic.name);
      if (!topic.producer.empty() && topic.producer != kind) {
        throw std::runtime_error("bus/Topics.hpp names '" + topic.producer + "' the producer of " + topic.name +
                                 ", but component '" + kind + "' writes it");
      }
    }
  }
  const auto producedBy = [&](const std::string& producer, TopicSet& allowed) {
    for (const auto& topic : topics) {
      const bool stepped = topic.qos == bus::QosKind::kStepped || topic.qos == bus::QosKind::kProtocol;
      if (stepped && topic.producer == producer) allowed.insert(topic.name);
    }
  };
  const std::string time_master(bus::topics::kStepGrant.producer);
  std::vector<Grant> grants;
  for (const auto& id : identities) {
    TopicSet allowed, readable;
    if (id == bus::kOperatorIdentity || id == kReplayIdentity) {
      // The tools (echo, health, record, the launcher) and replay's stand-in rig read anything.
      for (const auto& topic : topics) readable.insert(topic.name);
    } else if (const auto it = endpoints.find(id); it != endpoints.end()) {
      readable = it->second.read;
    } else {
      const auto* kind = findComponentKind(id);
      readable.insert(kind->reads.begin(), kind->reads.end());
    }
    if (id == bus::kOperatorIdentity) {
      // Commands: command topics without a producer that no component writes
      // (fault_cmd, unloading_mode_cmd, param_cmd); and the launcher's
      // "restarted" fault event (rig/Launcher.cpp, `flatsat run --restart`).
      for (const auto& topic : topics) {
        if (topic.qos == bus::QosKind::kCommand && topic.producer.empty() && !written_by_any.contains(topic.name)) {
          allowed.insert(topic.name);
        }
      }
      allowed.emplace(bus::topics::kFaultEvent.name);
    } else if (id == kReplayIdentity) {
      // `flatsat replay`: a time master that publishes recorded samples of any stepped topic.
      for (const auto& topic : topics) {
        if (topic.qos == bus::QosKind::kStepped) allowed.insert(topic.name);
      }
      const auto& master = endpoints.at(time_master).written;
      allowed.insert(master.begin(), master.end());
    } else {
      producedBy(id, allowed);
      if (const auto it = endpoints.find(id); it != endpoints.end()) {
        // What its code writes besides: health, step_done (stepped components),
        // command_ack and fault_event (those that take commands, bus::FaultPort,
        // bus::CommandAcks, the time master).
        allowed.insert(it->second.written.begin(), it->second.written.end());
      } else {
        // A process-only kind is a bus::Node, not stepped: its health, and a
        // hardware bridge `<producer>_bridge` its producer's stepped topics.
        allowed.emplace(bus::topics::kHealth.name);
        const std::string suffix = "_bridge";
        if (id.size() > suffix.size() && id.ends_with(suffix)) producedBy(id.substr(0, id.size() - suffix.size()), allowed);
      }
    }
    Grant grant{id, {}, {}};
    for (const auto& topic : topics) {
      if (allowed.contains(topic.name)) grant.publish.push_back(topic.name);
      if (readable.contains(topic.name)) grant.subscribe.push_back(topic.name);
    }
    grants.push_back(std::move(grant));
  }
  return grants;
}

CLI::App* addGrantsCommand(CLI::App& app, int& exit_code) {
  auto identities = std::make_shared<std::vector<std::string>>();
  auto* cmd = app.add_subcommand(
      "security-grants", "the DDS Security grants of the rig's identities: what each may publish and subscribe to");
  cmd->add_option("identity", *identities, "component kind, operator or replay (default: every one)");
  cmd->footer(
      "Prints per identity `IDENTITY publish TOPIC ...` and `IDENTITY subscribe TOPIC ...`;\n"
      "deploy/security/make-certs.sh signs them as grants. A component publishes the stepped\n"
      "topics bus/Topics.hpp names it the producer of and what its code writes besides\n"
      "(health, step_done, command_ack, fault_event: its node built on an in-process bus from\n"
      "a shipped scenario); a bridge <producer>_bridge its producer's stepped topics; operator\n"
      "the commands and fault_event; replay every stepped topic and what the time master\n"
      "writes. A component subscribes to what its node reads, operator and replay to every topic.");
  cmd->callback([identities, &exit_code] {
    runReportingErrors(exit_code, [&] {
      std::vector<Grant> grants;
      try {
        grants = securityGrants(*identities);
      } catch (const std::invalid_argument& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
      }
      for (const auto& grant : grants) {
        for (const auto& [verb, list] : {std::pair{"publish", &grant.publish}, std::pair{"subscribe", &grant.subscribe}}) {
          std::cout << grant.identity << " " << verb;
          for (const auto& topic : *list) std::cout << " " << topic;
          std::cout << "\n";
        }
      }
      return 0;
    });
  });
  return cmd;
}

}  // namespace flatsat::tools
