// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>

#include "bus/Qos.hpp"

namespace flatsat::bus {

class LocalHub;

/// Which network a participant may use.
enum class NetworkProfile {
  kLoopback,  ///< 127.0.0.1 + shared memory, unicast discovery only: nothing leaves the host
  kNetwork,   ///< UDP on every interface with multicast discovery (opt-in, for multi-host rigs)
  /// UDP only on this host's address among `peers`, unicast discovery to the
  /// peers, no shared memory, no multicast: a rig across hosts or namespaces
  kPeers,
  /// UDP only (no shared memory, no multicast), discovery through Fast DDS
  /// discovery servers (`fastdds discovery`) at `discovery_servers`: networks
  /// without multicast, such as a container network with it switched off
  kDiscoveryServer,
};

struct BusOptions {
  std::uint32_t domain_id = 0;  ///< [-] DDS domain, 0..232 (the port formula caps it)
  NetworkProfile profile = NetworkProfile::kLoopback;
  std::string participant_name = "flatsat";
  QosTuning tuning;  ///< applied to every endpoint of this participant
  /// kPeers: IPv4 addresses of the rig's hosts, this host's among them
  std::vector<std::string> peers;
  /// kDiscoveryServer: "IPv4:port" of each server, server i started with `-i i`
  std::vector<std::string> discovery_servers;
  /// DDS Security directory (bus/Security.hpp); "" for an open bus
  std::string security_dir;
  /// certificate and grant used with security_dir; "" means participant_name
  std::string identity;
  /// kLoopback: the shared-memory transport and data sharing besides UDP on
  /// 127.0.0.1; false: UDP only (BusNetwork::shared_memory)
  bool shared_memory = true;
  /// kLoopback with shared_memory: the endpoints' own traffic (acknowledgements,
  /// heartbeats) through shared memory too, not only data sharing's samples.
  /// For lockstep rigs, whose processes nobody stops on purpose (bus/Bus.cpp).
  bool acks_over_shm = false;
};

/// A process's network from its environment: FLATSAT_PEERS=a,b,... selects
/// kPeers with those hosts, FLATSAT_NETWORK=1 kNetwork,
/// FLATSAT_DISCOVERY_SERVER=host:port[,host:port] kDiscoveryServer (host names
/// resolved here), none of them kLoopback; FLATSAT_SECURE_DIR turns DDS
/// Security on.
struct BusNetwork {
  NetworkProfile profile = NetworkProfile::kLoopback;
  std::vector<std::string> peers;
  std::vector<std::string> discovery_servers;  ///< "IPv4:port", resolved
  std::string security_dir;  ///< FLATSAT_SECURE_DIR: DDS Security on, with that directory's files
  /// FLATSAT_SHARED_MEMORY=0: no shared memory between processes (UDP on
  /// 127.0.0.1 only, data sharing off), for rigs with a process that may be
  /// stopped (a debugger, SIGSTOP): Fast DDS gives up an interprocess lock
  /// after 1 s and aborts the peer waiting on one the stopped process holds.
  bool shared_memory = true;
};

/// Domain id for a process: FLATSAT_DOMAIN overrides the scenario's value.
std::uint32_t domainFromEnvironment(std::uint32_t scenario_domain);
/// Throws std::invalid_argument naming the variable when it is malformed.
BusNetwork networkFromEnvironment();
/// Puts a process's network (profile, peers, servers, security) into `options`.
void useNetwork(BusOptions& options, const BusNetwork& network);
/// The IPv4 addresses of this host's (this network namespace's) interfaces.
std::vector<std::string> ownAddresses();

/// One DDS participant with one publisher and two subscribers (readers that
/// watch their writers' liveliness, and the others: createReader); topics
/// are created once per name and shared by every endpoint of the process.
/// Or, in a composed rig, an in-process bus: the endpoints go to a LocalHub
/// and no participant exists (nothing on the network or in /dev/shm).
class Bus : private eprosima::fastdds::dds::DomainParticipantListener {
 public:
  explicit Bus(const BusOptions& options);
  /// In-process: domain and network in `options` are unused; `hub` outlives the bus.
  Bus(const BusOptions& options, LocalHub& hub);
  ~Bus();
  Bus(const Bus&) = delete;
  Bus& operator=(const Bus&) = delete;

  /// The hub of an in-process bus; null for a DDS bus.
  LocalHub* localHub() const { return hub_; }
  /// The DDS entities; throw std::logic_error on an in-process bus.
  eprosima::fastdds::dds::DomainParticipant& participant() { return *ddsEntity(participant_); }
  eprosima::fastdds::dds::Publisher& publisher() { return *ddsEntity(publisher_); }
  std::uint32_t domainId() const { return options_.domain_id; }
  const QosTuning& tuning() const { return options_.tuning; }

  /// Samples received on any reader of this participant that did not decode,
  /// and those Fast DDS dropped or lost before (bus/FastDdsLog.hpp).
  std::uint64_t samplesDropped() const { return samples_dropped_.load(); }
  /// Counts a dropped sample, `what`: its type and why; logs the 1st, 10th, 100th, ...
  void countDroppedSample(const char* what);
  /// What this bus's topic types (GuardedType) call for each sample that does not decode.
  std::function<void(const char*)> dropCounter() {
    return [this](const char* type_name) { countDroppedSample((std::string(type_name) + " that does not decode").c_str()); };
  }

  /// The name a discovered participant gave itself (its component's name in a
  /// rig); nothing when it is unknown or gone. Names are what a writer's
  /// producer is checked against (Reader's trust): on an open bus anyone may
  /// take any name, and DDS Security's grants are what make them binding.
  /// A tool that sets a participant listener of its own (ToolBus) has none.
  std::optional<std::string> participantName(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) const;

  /// Commands this participant refused (bus::CommandAcks), for health.
  std::uint64_t commandsRefused() const { return commands_refused_.load(); }
  /// Counts and logs (warning) a refused command with its reason.
  void countRefusedCommand(const std::string& command, std::uint64_t command_id,
                           const std::string& reason);

  /// The topic of that name, registering its type on first use (takes `type`).
  eprosima::fastdds::dds::Topic& topic(const std::string& name,
                                       eprosima::fastdds::dds::TopicDataType* type);

  /// Every reader of the participant is made and deleted here. Watchers (readers of a
  /// finite lease) have a subscriber of their own, unmatched while a reader is made or
  /// deleted: Fast DDS 2.9.1 walks its readers unlocked on each liveliness change, and a
  /// reader made mid-walk leaves the walk on freed memory.
  /// Throws std::runtime_error naming the participant and topic when Fast DDS refuses the reader.
  eprosima::fastdds::dds::DataReader* createReader(eprosima::fastdds::dds::Topic& topic,
                                                   const eprosima::fastdds::dds::DataReaderQos& qos,
                                                   eprosima::fastdds::dds::DataReaderListener* listener);
  void deleteReader(eprosima::fastdds::dds::DataReader* reader);

  /// Keeps the watchers unmatched while it lives, so that a batch of
  /// readers (a node's, made at its start or deleted at its end) costs one
  /// rematch, not one per reader. Nothing on an in-process bus.
  class WatchersHeld {
   public:
    explicit WatchersHeld(Bus& bus);
    ~WatchersHeld();
    WatchersHeld(const WatchersHeld&) = delete;
    WatchersHeld& operator=(const WatchersHeld&) = delete;

   private:
    Bus& bus_;
  };

 private:
  void holdWatchers();     // with readers_mutex_ held
  void releaseWatchers();  // with readers_mutex_ held
  void matchWatchers(bool match);

  template <class Entity>
  Entity* ddsEntity(Entity* entity) const {
    if (hub_ != nullptr) {
      throw std::logic_error(options_.participant_name + ": an in-process bus has no DDS participant");
    }
    return entity;
  }

  BusOptions options_;
  LocalHub* hub_ = nullptr;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  eprosima::fastdds::dds::Subscriber* watch_subscriber_ = nullptr;
  std::mutex readers_mutex_;
  int watchers_held_ = 0;           // WatchersHeld alive, and readers being made or deleted
  std::size_t watchers_ = 0;        // readers in watch_subscriber_
  bool watchers_matching_ = false;  // watch_subscriber_ in the rig's partition
  bool closing_ = false;            // ~Bus: the watchers stay unmatched
  std::mutex mutex_;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;
  mutable std::mutex participants_mutex_;
  std::map<eprosima::fastrtps::rtps::GuidPrefix_t, std::string> participants_;  // discovered, by GUID prefix
  std::atomic<std::uint64_t> samples_dropped_{0};
  std::atomic<std::uint64_t> commands_refused_{0};
};

}  // namespace flatsat::bus
