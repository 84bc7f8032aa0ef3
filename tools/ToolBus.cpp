// SPDX-License-Identifier: Apache-2.0
#include "bus/InstallPaths.hpp"
#include "tools/ToolBus.hpp"

#include <sstream>

#include <filesystem>
#include <thread>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/rtps/builtin/data/ParticipantProxyData.h>
#include <fastdds/rtps/builtin/data/WriterProxyData.h>

#include "bus/Scenario.hpp"
#include "bus/Security.hpp"
#include "bus/Shutdown.hpp"

namespace flatsat::tools {

namespace dds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;

namespace {

/// The default scenario's domain, so `flatsat run` and a bare tool meet.
std::uint32_t defaultScenarioDomain() {
  if (const auto candidate = bus::findIn(bus::scenarioDirs(), "default.yaml")) {
    try {
      return bus::loadScenario(candidate->string()).domain_id;
    } catch (const std::exception&) {
      // an unreadable default scenario is not this tool's problem
    }
  }
  return 0;
}

/// Creates the participant disabled, so the listener is in place before
/// the first discovery message can arrive, then enables it.
std::unique_ptr<bus::Bus> disabledBus(const bus::BusOptions& options) {
  auto* factory = dds::DomainParticipantFactory::get_instance();
  dds::DomainParticipantFactoryQos qos;
  factory->get_qos(qos);
  qos.entity_factory().autoenable_created_entities = false;
  factory->set_qos(qos);
  std::unique_ptr<bus::Bus> created;
  try {
    created = std::make_unique<bus::Bus>(options);
  } catch (...) {
    qos.entity_factory().autoenable_created_entities = true;
    factory->set_qos(qos);
    throw;
  }
  qos.entity_factory().autoenable_created_entities = true;
  factory->set_qos(qos);
  return created;
}

}  // namespace

void addDomainOption(CLI::App& command, int& domain) {
  command
      .add_option("--domain", domain,
                  "DDS domain of the rig (default: FLATSAT_DOMAIN, else the default scenario's)")
      ->check(CLI::Range(0, 232));
}

std::uint32_t resolveDomain(int domain_option) {
  if (domain_option >= 0) return static_cast<std::uint32_t>(domain_option);
  return bus::domainFromEnvironment(defaultScenarioDomain());
}

ToolBus::ToolBus(const std::string& tool_name, int domain_option)
    : domain_(resolveDomain(domain_option)) {
  bus::BusOptions options;
  options.domain_id = domain_;
  bus::useNetwork(options, bus::networkFromEnvironment());
  options.identity = bus::kOperatorIdentity;
  options.participant_name = "flatsat-" + tool_name;
  bus_ = disabledBus(options);
  bus_->participant().set_listener(this, dds::StatusMask::none());
  if (bus_->participant().enable() != ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error("could not enable the DDS participant on domain " +
                             std::to_string(domain_));
  }
  std::lock_guard lock(mutex_);
  own_prefix_ = bus_->participant().guid().guidPrefix;
}

ToolBus::~ToolBus() {
  if (bus_) bus_->participant().set_listener(nullptr);
  bus_.reset();
}

void ToolBus::on_participant_discovery(dds::DomainParticipant*,
                                       rtps::ParticipantDiscoveryInfo&& info) {
  std::lock_guard lock(mutex_);
  auto& entry = participants_[info.info.m_guid.guidPrefix];
  switch (info.status) {
    case rtps::ParticipantDiscoveryInfo::DISCOVERED_PARTICIPANT:
    case rtps::ParticipantDiscoveryInfo::CHANGED_QOS_PARTICIPANT:
      entry.name = info.info.m_participantName.to_string();
      entry.alive = true;
      break;
    case rtps::ParticipantDiscoveryInfo::REMOVED_PARTICIPANT:
    case rtps::ParticipantDiscoveryInfo::DROPPED_PARTICIPANT:
      entry.alive = false;
      for (auto& [guid, writer] : writers_) {
        if (guid.guidPrefix == info.info.m_guid.guidPrefix) writer.alive = false;
      }
      break;
  }
}

void ToolBus::on_publisher_discovery(dds::DomainParticipant*, rtps::WriterDiscoveryInfo&& info) {
  std::lock_guard lock(mutex_);
  auto& entry = writers_[info.info.guid()];
  entry.guid = info.info.guid();
  entry.topic = info.info.topicName().to_string();
  entry.type = info.info.typeName().to_string();
  entry.ownership_strength = static_cast<std::int32_t>(info.info.m_qos.m_ownershipStrength.value);
  entry.alive = info.status != rtps::WriterDiscoveryInfo::REMOVED_WRITER;
}

void ToolBus::on_subscriber_discovery(dds::DomainParticipant*, rtps::ReaderDiscoveryInfo&& info) {
  std::lock_guard lock(mutex_);
  readers_[info.info.guid()] = {info.info.topicName().to_string(),
                                info.status != rtps::ReaderDiscoveryInfo::REMOVED_READER};
}

bool ToolBus::readerDiscovered(const std::string& topic, const std::string& participant) const {
  std::lock_guard lock(mutex_);
  for (const auto& [guid, reader] : readers_) {
    if (!reader.second || reader.first != topic) continue;
    const auto it = participants_.find(guid.guidPrefix);
    if (it != participants_.end() && it->second.alive && it->second.name == participant) return true;
  }
  return false;
}

int ToolBus::readersDiscovered(const std::string& topic) const { return static_cast<int>(readersOf(topic).size()); }

std::map<GuidPrefix, ParticipantInfo> ToolBus::participants() const {
  std::lock_guard lock(mutex_);
  auto out = participants_;
  out.erase(own_prefix_);
  return out;
}

std::vector<Guid> ToolBus::readersOf(const std::string& topic) const {
  std::lock_guard lock(mutex_);
  std::vector<Guid> out;
  for (const auto& [guid, reader] : readers_) {
    const auto it = participants_.find(guid.guidPrefix);
    if (reader.second && reader.first == topic && it != participants_.end() && it->second.alive) out.push_back(guid);
  }
  return out;
}

std::vector<WriterInfo> ToolBus::writers() const {
  std::lock_guard lock(mutex_);
  std::vector<WriterInfo> out;
  for (const auto& [guid, writer] : writers_) out.push_back(writer);
  return out;
}

std::string ToolBus::participantName(const GuidPrefix& prefix) const {
  std::lock_guard lock(mutex_);
  auto it = participants_.find(prefix);
  return it == participants_.end() ? std::string() : it->second.name;
}

std::string_view shortTopicName(std::string_view topic) {
  const auto slash = topic.rfind('/');
  return slash == std::string_view::npos ? topic : topic.substr(slash + 1);
}

std::string registryTopicNames() {
  std::string names;
  bus::forEachTopic([&](const auto& def) {
    if (!names.empty()) names += ", ";
    names += def.name;
  });
  return names;
}

bool sleepUnlessInterrupted(double seconds, double check_every_s) {
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(seconds));
  const auto slice = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(check_every_s));
  while (Clock::now() < end) {
    if (bus::shutdownRequested()) return false;
    std::this_thread::sleep_for(std::min<Clock::duration>(slice, end - Clock::now()));
  }
  return !bus::shutdownRequested();
}

void flattenJson(const nlohmann::ordered_json& value, const std::string& path,
                 std::vector<std::pair<std::string, const nlohmann::ordered_json*>>& out) {
  if (value.is_object()) {
    for (const auto& [key, item] : value.items()) {
      flattenJson(item, path.empty() ? key : path + "." + key, out);
    }
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      flattenJson(value[i], path + "[" + std::to_string(i) + "]", out);
    }
  } else {
    out.emplace_back(path, &value);
  }
}

std::string guidText(const Guid& guid) {
  std::ostringstream out;
  out << guid;
  return out.str();
}

const nlohmann::ordered_json* fieldOf(const nlohmann::ordered_json& sample, std::string_view path) {
  const nlohmann::ordered_json* at = &sample;
  std::size_t i = 0;
  while (i < path.size()) {
    if (path[i] == '[') {
      const auto close = path.find(']', i);
      if (close == std::string_view::npos || close == i + 1 || !at->is_array()) return nullptr;
      std::size_t index = 0;
      for (const char c : path.substr(i + 1, close - i - 1)) {
        if (c < '0' || c > '9') return nullptr;
        index = index * 10 + static_cast<std::size_t>(c - '0');
      }
      if (index >= at->size()) return nullptr;
      at = &(*at)[index];
      i = close + 1;
      continue;
    }
    if (path[i] == '.') {
      if (i == 0) return nullptr;
      ++i;
    }
    const auto end = path.find_first_of(".[", i);
    const auto key = path.substr(i, end == std::string_view::npos ? std::string_view::npos : end - i);
    if (key.empty() || !at->is_object()) return nullptr;
    const auto it = at->find(std::string(key));
    if (it == at->end()) return nullptr;
    at = &*it;
    i = end == std::string_view::npos ? path.size() : end;
  }
  return at;
}

}  // namespace flatsat::tools
