// SPDX-License-Identifier: Apache-2.0
#pragma once
// What the live operator tools (topics, echo, hz, health) share: a DDS
// participant that joins any rig's domain and remembers what discovery saw.
// They read with bus::Reader's watching constructor (every sample with its
// writer and arrival time). The tools know the topic registry, never the scenario.
#include <chrono>
#include <cstdint>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>

#include "bus/Bus.hpp"
#include "bus/Endpoints.hpp"
#include "bus/Topics.hpp"
#include "msg/MsgJson.hpp"

namespace flatsat::tools {

using Clock = std::chrono::steady_clock;
using Guid = eprosima::fastrtps::rtps::GUID_t;
using GuidPrefix = eprosima::fastrtps::rtps::GuidPrefix_t;

/// [s] How long a tool needs to see the whole rig. A component learns of a
/// new participant from that participant's announcements but answers only
/// with its own periodic one (Fast DDS's announcement period, 3 s by default,
/// which bus::Bus keeps), so a tool finds each component 0..3 s after it
/// joined; endpoint matching and transient-local history follow at once.
inline constexpr double kDiscoverySeconds = 4.0;

/// Adds `--domain N` to a tool; unset (-1), the domain is FLATSAT_DOMAIN,
/// else the default scenario's.
void addDomainOption(CLI::App& command, int& domain);
std::uint32_t resolveDomain(int domain_option);

/// A writer that discovery announced.
struct WriterInfo {
  std::string topic;
  std::string type;
  Guid guid;
  std::int32_t ownership_strength = 0;
  bool alive = true;  ///< false once the writer was removed
};

/// A participant that discovery announced.
struct ParticipantInfo {
  std::string name;   ///< the rig names each component's participant after the component
  bool alive = true;  ///< false once it left or was dropped
};

/// A tool's participant: loopback like every component, and a record of
/// discovery from the first announcement on (the participant is enabled
/// only after its listener is in place, so nothing is missed).
class ToolBus : private eprosima::fastdds::dds::DomainParticipantListener {
 public:
  ToolBus(const std::string& tool_name, int domain_option);
  ~ToolBus() override;
  ToolBus(const ToolBus&) = delete;
  ToolBus& operator=(const ToolBus&) = delete;

  bus::Bus& bus() { return *bus_; }
  std::uint32_t domain() const { return domain_; }
  /// Remote participants by GUID prefix (this tool's own excluded).
  std::map<GuidPrefix, ParticipantInfo> participants() const;
  std::vector<WriterInfo> writers() const;
  /// The participant name of a writer's participant; "" when unknown.
  std::string participantName(const GuidPrefix& prefix) const;
  /// Whether discovery announced a live reader of `topic` in the participant
  /// named `participant` (Fast DDS 2.9 cannot list a writer's matched readers:
  /// DataWriter::get_matched_subscriptions returns RETCODE_UNSUPPORTED).
  bool readerDiscovered(const std::string& topic, const std::string& participant) const;
  /// How many live readers of `topic` discovery announced, in any participant.
  int readersDiscovered(const std::string& topic) const;
  /// The live readers of `topic` discovery announced, by GUID.
  std::vector<Guid> readersOf(const std::string& topic) const;

 private:
  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant* participant,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;
  void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant* participant,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override;
  void on_subscriber_discovery(eprosima::fastdds::dds::DomainParticipant* participant,
                               eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override;

  std::uint32_t domain_;
  mutable std::mutex mutex_;
  GuidPrefix own_prefix_;
  std::map<GuidPrefix, ParticipantInfo> participants_;
  std::map<Guid, WriterInfo> writers_;
  std::map<Guid, std::pair<std::string, bool>> readers_;  // topic, alive
  std::unique_ptr<bus::Bus> bus_;  // last: destroyed first, before what its callbacks touch
};

/// A sample's arrival, as bus::Reader's watching constructor (the one the
/// tools read with) hands it over.
using bus::Arrival;

/// A GUID as Fast DDS prints it ("01.0f.…|0.0.6.3").
std::string guidText(const Guid& guid);

/// "truth" for "flatsat/truth".
std::string_view shortTopicName(std::string_view topic);
/// Every registry topic, comma separated (for error messages).
std::string registryTopicNames();

/// Calls f(def) for the registry topic named `name` (full or short name);
/// false when there is none.
template <class F>
bool withTopic(std::string_view name, F&& f) {
  bool found = false;
  bus::forEachTopic([&](const auto& def) {
    if (!found && (def.name == name || shortTopicName(def.name) == name)) {
      found = true;
      f(def);
    }
  });
  return found;
}

/// The exit code of `run(def)` for the registry topic named `name`: 2 (with
/// the known topics listed) when there is none, 1 when it throws.
template <class Run>
int runForTopic(std::string_view name, Run&& run) {
  try {
    int code = 0;
    if (withTopic(name, [&](const auto& def) { code = run(def); })) return code;
    std::cerr << "error: unknown topic '" << name << "'; topics: " << registryTopicNames() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

/// Waits `seconds` of wall time, returning early (false) on SIGINT/SIGTERM,
/// which it looks for every `check_every_s`.
bool sleepUnlessInterrupted(double seconds, double check_every_s = 0.05);

/// Flattens a JSON sample into (path, leaf) pairs in order: objects by
/// ".key", arrays by "[i]"; the paths are the generated leafFields<T>().
void flattenJson(const nlohmann::ordered_json& value, const std::string& path,
                 std::vector<std::pair<std::string, const nlohmann::ordered_json*>>& out);

/// The part of a JSON sample at `path`, in flattenJson's spelling
/// ("header.step", "w_body_rad_s", "w_body_rad_s[2]"); nullptr when it has none.
const nlohmann::ordered_json* fieldOf(const nlohmann::ordered_json& sample, std::string_view path);

}  // namespace flatsat::tools
