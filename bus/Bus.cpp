// SPDX-License-Identifier: Apache-2.0
#include "bus/Bus.hpp"
#include "bus/LoopbackQos.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netdb.h>
#include <netinet/in.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <spdlog/spdlog.h>

#include "bus/FastDdsLog.hpp"
#include "bus/Security.hpp"

namespace flatsat::bus {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

namespace {

constexpr std::uint32_t kMaxDomainId = 232;  // 7400 + 250 d + offsets must stay below 65535
/// Participants per host that unicast discovery reaches. Each is one
/// metatraffic port; the rig plus tools stays well below it.
constexpr std::uint32_t kMaxLocalParticipants = 48;
/// The watchers' partition while they are held (Bus::createReader): no writer of the rig has one.
constexpr const char* kWatchersHeldPartition = "flatsat.watchers-held";

Locator_t udpLocator(const std::string& address, std::uint32_t port) {
  Locator_t locator;
  locator.kind = LOCATOR_KIND_UDPv4;
  IPLocator::setIPv4(locator, address);
  locator.port = port;
  return locator;
}

Locator_t loopbackLocator(std::uint32_t port) { return udpLocator("127.0.0.1", port); }

/// Unicast discovery: SPDP goes to the metatraffic ports of the first
/// participants of the domain on each host (RTPS 2.2 §9.6.1.1 port mapping:
/// 7400 + 250 domain + 10 + 2 participant id).
void addInitialPeers(dds::DomainParticipantQos& qos, std::uint32_t domain,
                     const std::vector<std::string>& hosts) {
  auto& builtin = qos.wire_protocol().builtin;
  const auto& ports = qos.wire_protocol().port;
  for (const auto& host : hosts) {
    for (std::uint32_t id = 0; id < kMaxLocalParticipants; ++id) {
      builtin.initialPeersList.push_back(udpLocator(host, ports.getUnicastPort(domain, id)));
    }
  }
}

}  // namespace

/// Transports are set here, in code, from a default-constructed QoS: a
/// profile named only by FASTRTPS_DEFAULT_PROFILES_FILE cannot widen them.
/// Discovery is unicast to the metatraffic ports of the first participants
/// of the domain on 127.0.0.1 (RTPS 2.2 §9.6.1.1 port mapping), as ROS 2's
/// localhost-only mode does, so no multicast is ever sent.
/// `acks_over_shm`: the endpoints' own traffic (the acknowledgements a
/// data-sharing reader sends for every sample it takes, heartbeats, the
/// samples of peers without data sharing) goes through shared memory, not
/// UDP loopback. In lockstep that was 80 datagrams a step, and the rig's
/// system time fell by 30 % without them (tcpdump on lo, time).
/// Paced rigs and the tools keep UDP: processes are killed and stopped there
/// on purpose, and a peer stopped while it holds a shared-memory port's lock
/// wedges the others (Fast DDS 2.9.1's 1 s interprocess lock timeout); a
/// datagram never does.
dds::DomainParticipantQos loopbackParticipantQos(std::uint32_t domain, bool shared_memory, bool acks_over_shm) {
  dds::DomainParticipantQos qos;
  qos.transport().use_builtin_transports = false;
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->interfaceWhiteList.emplace_back("127.0.0.1");
  if (shared_memory) {
    qos.transport().user_transports.push_back(
        std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>());
  }
  qos.transport().user_transports.push_back(udp);

  auto& builtin = qos.wire_protocol().builtin;
  builtin.metatrafficMulticastLocatorList.clear();
  builtin.metatrafficUnicastLocatorList.push_back(loopbackLocator(0));
  // Empty, Fast DDS takes every transport's default: shared memory first.
  if (!(shared_memory && acks_over_shm)) {
    qos.wire_protocol().default_unicast_locator_list.push_back(loopbackLocator(0));
  }
  addInitialPeers(qos, domain, {"127.0.0.1"});
  return qos;
}

std::vector<std::string> ownAddresses() {
  std::vector<std::string> addresses;
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return addresses;
  for (const ifaddrs* it = list; it != nullptr; it = it->ifa_next) {
    if (it->ifa_addr == nullptr || it->ifa_addr->sa_family != AF_INET) continue;
    char text[INET_ADDRSTRLEN] = {};
    const auto* in = reinterpret_cast<const sockaddr_in*>(it->ifa_addr);
    ::inet_ntop(AF_INET, &in->sin_addr, text, sizeof text);
    addresses.emplace_back(text);
  }
  ::freeifaddrs(list);
  return addresses;
}

namespace {

/// The rig across hosts: this host's address among the peers is the only
/// interface, for data and discovery alike. The shared-memory transport is
/// off: network namespaces (and containers) often share one /dev/shm, and
/// Fast DDS would carry the traffic through it instead of the network the rig
/// tests. Data sharing (DATA_SHARING AUTO) still joins writers and readers
/// with the same host id, which Fast DDS derives from the interface
/// addresses: processes of one namespace or machine, never two.
dds::DomainParticipantQos peersQos(std::uint32_t domain, const std::vector<std::string>& peers) {
  std::string own;
  const auto local = ownAddresses();
  for (const auto& peer : peers) {
    if (std::find(local.begin(), local.end(), peer) != local.end()) own = peer;
  }
  if (own.empty()) {
    std::string held;
    for (const auto& a : local) held += " " + a;
    throw std::invalid_argument("FLATSAT_PEERS: none of the peers is an address of this host"
                                " (it has:" + held + "); list this host's rig address too");
  }
  dds::DomainParticipantQos qos;
  qos.transport().use_builtin_transports = false;
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->interfaceWhiteList.emplace_back(own);
  qos.transport().user_transports.push_back(udp);
  auto& builtin = qos.wire_protocol().builtin;
  builtin.metatrafficMulticastLocatorList.clear();
  builtin.metatrafficUnicastLocatorList.push_back(udpLocator(own, 0));
  qos.wire_protocol().default_unicast_locator_list.push_back(udpLocator(own, 0));
  addInitialPeers(qos, domain, peers);
  return qos;
}

dds::DomainParticipantQos networkQos() {
  dds::DomainParticipantQos qos;  // built-in UDPv4 + SHM, SPDP multicast
  return qos;
}

/// A discovery-server client (Fast DDS Discovery Server protocol): it
/// announces itself to the listed servers only and learns its peers from
/// them, so no multicast is needed or sent. Server i is the one started as
/// `fastdds discovery -i i`, whose GUID prefix Fast DDS derives from i. UDP
/// only: every process of such a rig is a host (container) of its own.
dds::DomainParticipantQos discoveryServerQos(const std::vector<std::string>& servers) {
  dds::DomainParticipantQos qos;
  qos.transport().use_builtin_transports = false;
  qos.transport().user_transports.push_back(
      std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>());
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.discoveryProtocol = eprosima::fastrtps::rtps::DiscoveryProtocol_t::CLIENT;
  qos.wire_protocol().builtin.metatrafficMulticastLocatorList.clear();
  for (std::size_t i = 0; i < servers.size(); ++i) {
    const auto colon = servers[i].rfind(':');
    eprosima::fastdds::rtps::RemoteServerAttributes server;
    eprosima::fastdds::rtps::get_server_client_default_guidPrefix(static_cast<int>(i),
                                                                 server.guidPrefix);
    server.metatrafficUnicastLocatorList.push_back(udpLocator(
        servers[i].substr(0, colon), static_cast<std::uint32_t>(std::stoul(servers[i].substr(colon + 1)))));
    discovery.m_DiscoveryServers.push_back(server);
  }
  return qos;
}

/// "host:port" with host a name or a dotted quad, into "IPv4:port".
std::string resolveServer(const std::string& entry, const std::string& variable) {
  const auto colon = entry.rfind(':');
  const auto bad = [&](const std::string& why) {
    return std::invalid_argument(variable + ": '" + entry + "': " + why);
  };
  if (colon == std::string::npos || colon == 0) throw bad("expected host:port");
  const std::string host = entry.substr(0, colon);
  const std::string port = entry.substr(colon + 1);
  char* end = nullptr;
  const unsigned long number = std::strtoul(port.c_str(), &end, 10);
  if (port.empty() || *end != '\0' || number == 0 || number > 65535) throw bad("port must be 1..65535");
  addrinfo hints{};
  hints.ai_family = AF_INET;
  addrinfo* found = nullptr;
  if (const int rc = ::getaddrinfo(host.c_str(), nullptr, &hints, &found); rc != 0) {
    throw bad(std::string("cannot resolve the host: ") + ::gai_strerror(rc));
  }
  char text[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(found->ai_addr)->sin_addr, text, sizeof text);
  ::freeaddrinfo(found);
  return std::string(text) + ":" + port;
}

}  // namespace

std::uint32_t domainFromEnvironment(std::uint32_t scenario_domain) {
  const char* text = std::getenv("FLATSAT_DOMAIN");
  if (text == nullptr || *text == '\0') return scenario_domain;
  char* end = nullptr;
  const unsigned long value = std::strtoul(text, &end, 10);
  if (*end != '\0' || value > kMaxDomainId) {
    throw std::invalid_argument("FLATSAT_DOMAIN='" + std::string(text) +
                                "': must be an integer in 0.." + std::to_string(kMaxDomainId));
  }
  return static_cast<std::uint32_t>(value);
}

BusNetwork networkFromEnvironment() {
  BusNetwork network;
  network.security_dir = securityDirFromEnvironment();
  const char* multicast = std::getenv("FLATSAT_NETWORK");
  if (multicast != nullptr && std::string(multicast) == "1") network.profile = NetworkProfile::kNetwork;
  if (const char* shm = std::getenv("FLATSAT_SHARED_MEMORY"); shm != nullptr && *shm != '\0') {
    if (std::string(shm) != "0" && std::string(shm) != "1") {
      throw std::invalid_argument("FLATSAT_SHARED_MEMORY='" + std::string(shm) + "': must be 0 or 1");
    }
    network.shared_memory = std::string(shm) == "1";
  }
  const char* servers = std::getenv("FLATSAT_DISCOVERY_SERVER");
  const char* peers = std::getenv("FLATSAT_PEERS");
  const bool has_servers = servers != nullptr && *servers != '\0';
  const bool has_peers = peers != nullptr && *peers != '\0';
  if (int(has_servers) + int(has_peers) + int(network.profile == NetworkProfile::kNetwork) > 1) {
    throw std::invalid_argument(
        "FLATSAT_PEERS, FLATSAT_DISCOVERY_SERVER and FLATSAT_NETWORK=1: choose one");
  }
  if (has_servers) {
    network.profile = NetworkProfile::kDiscoveryServer;
    std::istringstream list(servers);
    for (std::string server; std::getline(list, server, ',');) {
      network.discovery_servers.push_back(resolveServer(server, "FLATSAT_DISCOVERY_SERVER"));
    }
    return network;
  }
  if (!has_peers) return network;
  network.profile = NetworkProfile::kPeers;
  std::istringstream list(peers);
  for (std::string peer; std::getline(list, peer, ',');) {
    in_addr parsed{};
    if (::inet_pton(AF_INET, peer.c_str(), &parsed) != 1) {
      throw std::invalid_argument("FLATSAT_PEERS='" + std::string(peers) + "': '" + peer +
                                  "' is not an IPv4 address (a,b,c: dotted quads)");
    }
    network.peers.push_back(peer);
  }
  return network;
}

void useNetwork(BusOptions& options, const BusNetwork& network) {
  options.profile = network.profile;
  options.peers = network.peers;
  options.discovery_servers = network.discovery_servers;
  options.security_dir = network.security_dir;
  options.shared_memory = network.shared_memory;
}

Bus::Bus(const BusOptions& options) : options_(options) {
  if (!options.shared_memory) options_.tuning.data_sharing = false;
  if (options.domain_id > kMaxDomainId) {
    throw std::invalid_argument("domain id " + std::to_string(options.domain_id) +
                                ": must be in 0.." + std::to_string(kMaxDomainId));
  }
  auto qos = options.profile == NetworkProfile::kLoopback
                 ? loopbackParticipantQos(options.domain_id, options.shared_memory, options.acks_over_shm)
             : options.profile == NetworkProfile::kPeers ? peersQos(options.domain_id, options.peers)
             : options.profile == NetworkProfile::kDiscoveryServer
                 ? discoveryServerQos(options.discovery_servers)
                 : networkQos();
  qos.name(options.participant_name);
  if (!options.security_dir.empty()) {
    addSecurity(qos, options.security_dir,
                options.identity.empty() ? options.participant_name : options.identity);
  }
  // Listening from the creation on: a peer discovered before a listener was set would stay nameless.
  participant_ = dds::DomainParticipantFactory::get_instance()->create_participant(
      options.domain_id, qos, this, dds::StatusMask::none());
  if (participant_ == nullptr) {
    throw std::runtime_error(
        "could not create a DDS participant on domain " + std::to_string(options.domain_id) +
        (options.security_dir.empty() ? std::string()
                                      : " with DDS Security from " + options.security_dir +
                                            " (a certificate or signed grant did not verify)"));
  }
  publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  dds::SubscriberQos held = dds::SUBSCRIBER_QOS_DEFAULT;
  held.partition().push_back(kWatchersHeldPartition);
  watch_subscriber_ = participant_->create_subscriber(held);
  if (publisher_ == nullptr || subscriber_ == nullptr || watch_subscriber_ == nullptr) {
    participant_->delete_contained_entities();
    dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
    throw std::runtime_error(options.participant_name + ": could not create the publisher and subscribers");
  }
  attachFastDdsLog(*this, {subscriber_, watch_subscriber_});
}

Bus::Bus(const BusOptions& options, LocalHub& hub) : options_(options), hub_(&hub) {}

Bus::~Bus() {
  if (participant_ == nullptr) return;  // in-process
  detachFastDdsLog(*this);
  {
    std::lock_guard lock(readers_mutex_);
    closing_ = true;  // the readers still here go with delete_contained_entities
    if (watchers_matching_) matchWatchers(false);
  }
  participant_->delete_contained_entities();
  participant_->set_listener(nullptr);
  dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

void Bus::on_participant_discovery(dds::DomainParticipant*,
                                   eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) {
  using Info = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo;
  std::lock_guard lock(participants_mutex_);
  if (info.status == Info::DISCOVERED_PARTICIPANT || info.status == Info::CHANGED_QOS_PARTICIPANT) {
    participants_[info.info.m_guid.guidPrefix] = info.info.m_participantName.to_string();
  } else {
    participants_.erase(info.info.m_guid.guidPrefix);
  }
}

std::optional<std::string> Bus::participantName(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) const {
  if (participant_ != nullptr && participant_->guid().guidPrefix == prefix) return options_.participant_name;
  std::lock_guard lock(participants_mutex_);
  if (const auto it = participants_.find(prefix); it != participants_.end()) return it->second;
  return std::nullopt;
}

void Bus::countDroppedSample(const char* what) {
  const std::uint64_t n = ++samples_dropped_;
  std::uint64_t decade = 1;  // a flood of bad samples does not flood the log
  while (decade <= n / 10) decade *= 10;
  if (n == decade) {
    spdlog::warn("{}: dropped a sample of {} ({} so far)", options_.participant_name, what, n);
  }
}

void Bus::countRefusedCommand(const std::string& command, std::uint64_t command_id,
                              const std::string& reason) {
  const std::uint64_t n = ++commands_refused_;
  spdlog::warn("{}: {} command {} refused ({} so far): {}", options_.participant_name, command,
               command_id, n, reason);
}

dds::Topic& Bus::topic(const std::string& name, dds::TopicDataType* type) {
  dds::TypeSupport support(type);  // owns `type` from here, also when the topic exists
  std::lock_guard lock(mutex_);
  ddsEntity(participant_);
  if (auto it = topics_.find(name); it != topics_.end()) return *it->second;
  support.register_type(participant_);
  dds::Topic* topic = participant_->create_topic(name, support.get_type_name(),
                                                 dds::TOPIC_QOS_DEFAULT);
  if (topic == nullptr) throw std::runtime_error("could not create topic " + name);
  topics_.emplace(name, topic);
  return *topic;
}

dds::DataReader* Bus::createReader(dds::Topic& topic, const dds::DataReaderQos& qos,
                                   dds::DataReaderListener* listener) {
  std::lock_guard lock(readers_mutex_);
  ddsEntity(participant_);
  const bool watches = !(qos.liveliness().lease_duration == eprosima::fastrtps::c_TimeInfinite);
  holdWatchers();
  dds::DataReader* reader =
      (watches ? watch_subscriber_ : subscriber_)->create_datareader(&topic, qos, listener, fastDdsReaderMask());
  if (reader != nullptr && watches) ++watchers_;
  releaseWatchers();
  if (reader == nullptr) {
    throw std::runtime_error(
        options_.participant_name + ": could not create a reader on " + topic.get_name() +
        (options_.security_dir.empty() || !watches
             ? std::string()
             : " under DDS Security: the grant must let it read in partition '" +
                   std::string(kWatchersHeldPartition) +
                   "', as deploy/security/make-certs.sh's grants do (make older files again)"));
  }
  return reader;
}

void Bus::deleteReader(dds::DataReader* reader) {
  std::lock_guard lock(readers_mutex_);
  const bool watches = reader->get_subscriber() == watch_subscriber_;
  holdWatchers();
  (watches ? watch_subscriber_ : subscriber_)->delete_datareader(reader);
  if (watches) --watchers_;
  releaseWatchers();
}

Bus::WatchersHeld::WatchersHeld(Bus& bus) : bus_(bus) {
  if (bus_.hub_ != nullptr) return;
  std::lock_guard lock(bus_.readers_mutex_);
  bus_.holdWatchers();
}

Bus::WatchersHeld::~WatchersHeld() {
  if (bus_.hub_ != nullptr) return;
  std::lock_guard lock(bus_.readers_mutex_);
  bus_.releaseWatchers();
}

void Bus::holdWatchers() {
  if (watchers_held_++ == 0 && watchers_matching_) matchWatchers(false);
}

void Bus::releaseWatchers() {
  if (--watchers_held_ == 0 && watchers_ > 0 && !closing_) matchWatchers(true);
}

void Bus::matchWatchers(bool match) {
  dds::SubscriberQos qos = watch_subscriber_->get_qos();
  qos.partition().clear();
  if (!match) qos.partition().push_back(kWatchersHeldPartition);
  // Fast DDS unmatches (and matches) the subscriber's readers within set_qos (EDP::updatedLocalReader).
  if (watch_subscriber_->set_qos(qos) != ReturnCode_t::RETCODE_OK) {
    spdlog::error("{}: could not move the liveliness watchers {} the rig's partition",
                  options_.participant_name, match ? "into" : "out of");
    return;
  }
  watchers_matching_ = match;
}

}  // namespace flatsat::bus
