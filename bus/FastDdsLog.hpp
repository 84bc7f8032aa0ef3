// SPDX-License-Identifier: Apache-2.0
#pragma once
// Fast DDS's own log, routed through spdlog with its repeats limited, and the
// samples Fast DDS drops before the bus's GuardedType sees them counted in
// the bus's samples_dropped. Header only; bus/Bus.cpp
// calls attachFastDdsLog once its participant and subscribers exist, gives
// every reader fastDdsReaderMask(), and calls detachFastDdsLog first thing
// in ~Bus.
//
// Where Fast DDS 2.9.1 drops such samples, and what it tells:
//
// * A payload larger than the type's maximum. A reader of a bounded type
//   (every registry type) keeps its history in PREALLOCATED_MEMORY_MODE
//   (DataReaderImpl::get_payload_pool turns the default
//   PREALLOCATED_WITH_REALLOC into it when type->is_bounded()) with
//   payloadMaxSize = m_typeSize + 3 (DataReaderHistory.cpp,
//   to_history_attributes). StatefulReader::processDataMsg and
//   processDataFragMsg (StatelessReader::processDataMsg for best-effort
//   readers) ask ReaderHistory::can_change_be_added_nts
//   (src/cpp/rtps/history/ReaderHistory.cpp), which logs
//   EPROSIMA_LOG_ERROR(RTPS_READER_HISTORY, "Change payload size of 'N' bytes
//   is larger than the history payload size of 'M' bytes and cannot be
//   resized.") and sets will_never_be_accepted; the reader then marks the
//   sample irrelevant (WriterProxy::irrelevant_change_set; stateless:
//   update_last_notified). No status changes and no listener is called:
//   not on_sample_rejected (only for history limits, from
//   StatefulReader::change_received and processDataFragMsg), not
//   on_sample_lost (an irrelevant sample is not lost,
//   WriterProxy::lost_changes_update). That log entry, one per sample and
//   reader, is its only trace: Consumer below counts it as a dropped sample
//   of the bus whose topic type has that M.
// * An empty payload from another process. Its writer sends a DATA
//   submessage without payload (DataMsgUtils::prepare_submessage_flags:
//   dataFlag needs length > 0), 20 bytes long, which
//   MessageReceiver::proc_Submsg_Data (src/cpp/rtps/messages/MessageReceiver.cpp)
//   drops as shorter than RTPSMESSAGE_DATA_MIN_LENGTH (24), logging at Info
//   level only, which Debian's build does not compile (HAVE_LOG_NO_INFO 1).
//   A reliable reader asks for the sample again at every heartbeat, gets the
//   same submessage, and holds back that writer's later samples (in order)
//   until the writer's history no longer has it; then the heartbeat's first
//   sequence number passes it and Fast DDS reports it lost
//   (WriterProxy::lost_changes_update -> on_sample_lost). A best-effort
//   reader reports it lost at the writer's next sample
//   (StatelessReader::processDataMsg). DropListener below counts those
//   reports (and any on_sample_rejected) as dropped samples of the reader's
//   bus; a sample a writer's keep-last history replaced before a reader had
//   it is reported lost the same way, and counted too, except on a state
//   topic (health), whose writers keep only their newest sample. From a writer in the
//   same process (intraprocess delivery) an empty sample reaches
//   GuardedType::deserialize, which counts it.
// tests/component/FastDdsRejectionsTest.cpp shows each of these.
#include <atomic>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <fastdds/dds/core/status/StatusMask.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/log/Log.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/SubscriberListener.hpp>
#include <fastdds/dds/topic/TopicDescription.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <spdlog/spdlog.h>

#include "bus/Bus.hpp"
#include "bus/Topics.hpp"

namespace flatsat::bus {

namespace fastdds_log {

namespace fdds = eprosima::fastdds::dds;

/// Distinct messages whose repeats are tracked; more share one count.
inline constexpr std::size_t kMaxTrackedMessages = 512;

/// The statuses a bus's subscribers listen to (DropListener) for its readers.
inline fdds::StatusMask dropStatuses() {
  auto mask = fdds::StatusMask::none();
  mask << fdds::StatusMask::sample_lost() << fdds::StatusMask::sample_rejected();
  return mask;
}

inline bool isStateTopic(const std::string& name) {
  bool state = false;
  forEachTopic([&](const auto& def) { state = state || (def.name == name && def.qos == QosKind::kState); });
  return state;
}

/// Counts what Fast DDS reports lost or rejected on a reader in the reader's
/// bus. One for the process, never freed: no callback outlives it.
class DropListener final : public fdds::SubscriberListener {
 public:
  void on_sample_lost(fdds::DataReader* reader, const fdds::SampleLostStatus& status) override {
    // A state topic (health) keeps each writer's newest sample only: one a
    // newer replaced before this reader had it is not lost data.
    if (isStateTopic(reader->get_topicdescription()->get_name())) return;
    count(reader, status.total_count_change, "reported lost by Fast DDS");
  }
  void on_sample_rejected(fdds::DataReader* reader, const fdds::SampleRejectedStatus& status) override {
    count(reader, status.total_count_change, "rejected by Fast DDS");
  }

 private:
  static void count(fdds::DataReader* reader, std::int32_t samples, const char* why);
};

/// What the consumer and the listener know of the process. Allocated once and
/// never freed: Fast DDS's log thread may consume entries during static
/// destruction.
struct State {
  DropListener drop_listener;
  std::mutex mutex;  // everything below, and a bus's life while it is counted in
  std::map<std::string, std::uint64_t> repeats;  // by category and message, numbers masked
  std::vector<Bus*> buses;                       // with a DDS participant, attach order
  std::map<std::pair<Bus*, std::uint32_t>, std::string> type_of;  // bus, payload maximum: type name found
  std::size_t next_bus = 0;                      // round robin among buses that could be the one
  std::atomic<std::uint64_t> rejected{0};        // oversized samples rejected, process-wide
  std::atomic<bool> exiting{false};              // exit() began: spdlog may be gone
};

inline State& state() {
  static State* const s = new State;
  return *s;
}

/// The key of a message's repeats: its category and text with every number
/// (a run of hex digits and separators holding a decimal digit: sizes,
/// sequence numbers, GUIDs, addresses) masked.
inline std::string repeatKey(const fdds::Log::Entry& entry) {
  std::string key = entry.context.category != nullptr ? entry.context.category : "";
  key += '|';
  const std::string& m = entry.message;
  const auto part = [](char c) {
    return std::isxdigit(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '|' || c == ':' || c == 'x';
  };
  for (std::size_t i = 0; i < m.size() && key.size() < 256;) {
    if (!part(m[i])) {
      key += m[i++];
      continue;
    }
    std::size_t end = i;
    bool digit = false;
    for (; end < m.size() && part(m[end]); ++end) {
      digit = digit || std::isdigit(static_cast<unsigned char>(m[end])) != 0;
    }
    key += digit ? std::string("#") : m.substr(i, end - i);
    i = end;
  }
  return key;
}

/// Whether the n-th occurrence is logged: the 1st, 10th, 100th, ...
inline bool isDecade(std::uint64_t n) {
  std::uint64_t decade = 1;
  while (decade <= n / 10) decade *= 10;
  return n == decade;
}

inline void DropListener::count(fdds::DataReader* reader, std::int32_t samples, const char* why) {
  if (samples <= 0) return;
  State& s = state();
  std::lock_guard lock(s.mutex);  // the bus stays while it is counted in
  const auto* participant = reader->get_subscriber()->get_participant();
  for (Bus* bus : s.buses) {
    if (&bus->participant() != participant) continue;
    const std::string what = reader->get_topicdescription()->get_type_name() + " (" + why + ")";
    for (std::int32_t i = 0; i < samples; ++i) bus->countDroppedSample(what.c_str());
    return;
  }
}

/// M of "... larger than the history payload size of 'M' bytes ...": the
/// rejecting reader's payload maximum (m_typeSize + 3); 0 for other entries.
inline std::uint32_t rejectedBy(const fdds::Log::Entry& entry) {
  static constexpr char kMarker[] = "is larger than the history payload size of '";
  const char* category = entry.context.category;
  if (category == nullptr || std::string(category) != "RTPS_READER_HISTORY") return 0;
  const auto at = entry.message.find(kMarker);
  if (at == std::string::npos) return 0;
  const char* digits = entry.message.c_str() + at + sizeof kMarker - 1;
  return static_cast<std::uint32_t>(std::strtoul(digits, nullptr, 10));
}

/// Counts a rejected sample in the bus with a registry topic of that
/// payload maximum (with state().mutex held). A process has one participant
/// as a rule; where several have such a topic, the count goes to each in
/// turn, as the log entry does not say which reader rejected the sample.
inline void countRejected(State& s, std::uint32_t payload_max) {
  std::vector<std::pair<Bus*, std::string>> candidates;  // bus, type name
  for (Bus* bus : s.buses) {
    if (const auto it = s.type_of.find({bus, payload_max}); it != s.type_of.end()) {
      candidates.emplace_back(bus, it->second);
      continue;
    }
    auto& participant = bus->participant();
    forEachTopic([&](const auto& def) {
      const auto* description = participant.lookup_topicdescription(std::string(def.name));
      if (description == nullptr || (!candidates.empty() && candidates.back().first == bus)) return;
      const auto type = participant.find_type(description->get_type_name());
      if (!type.empty() && type->m_typeSize + 3 == payload_max) {
        candidates.emplace_back(bus, description->get_type_name());
        s.type_of[{bus, payload_max}] = description->get_type_name();
      }
    });
  }
  if (candidates.empty()) return;
  const auto& [bus, type_name] = candidates[s.next_bus++ % candidates.size()];
  bus->countDroppedSample((type_name + " (larger than the type allows, rejected by Fast DDS)").c_str());
}

/// Fast DDS's log entries to spdlog at their level, each distinct message
/// (numbers masked) at its 1st, 10th, 100th, ... occurrence with its count;
/// and every oversized sample a reader rejected counted in its bus.
class Consumer final : public fdds::LogConsumer {
 public:
  void Consume(const fdds::Log::Entry& entry) override {
    using Kind = fdds::Log::Kind;
    State& s = state();
    std::lock_guard lock(s.mutex);
    if (const std::uint32_t payload_max = rejectedBy(entry); payload_max != 0) {
      ++s.rejected;
      if (!s.exiting) countRejected(s, payload_max);
    }
    std::string key = repeatKey(entry);
    if (s.repeats.size() >= kMaxTrackedMessages && s.repeats.count(key) == 0) key = "(other messages)";
    const std::uint64_t n = ++s.repeats[key];
    if (!isDecade(n)) return;
    const char* category = entry.context.category != nullptr ? entry.context.category : "";
    std::string text = entry.message;
    if (entry.context.function != nullptr) text += std::string(" (") + entry.context.function + ")";
    if (n > 1) text += " [" + std::to_string(n) + " times so far; logged at the 1st, 10th, 100th, ...]";
    const auto level = entry.kind == Kind::Error     ? spdlog::level::err
                       : entry.kind == Kind::Warning ? spdlog::level::warn
                                                     : spdlog::level::info;
    auto logger = s.exiting ? nullptr : spdlog::default_logger();
    if (logger) {
      logger->log(level, "fastdds [{}] {}", category, text);
    } else {
      std::fprintf(stderr, "fastdds [%s] %s\n", category, text.c_str());
    }
  }
};

/// Once per process: Fast DDS's consumers (its stderr one, or any a profile
/// file set) replaced by Consumer. Fast DDS's verbosity stays as it is
/// (Log::Error unless the process changed it).
inline void route() {
  static std::once_flag once;
  std::call_once(once, [] {
    state();
    spdlog::default_logger();  // spdlog's registry made before Fast DDS's log: it outlives it
    fdds::Log::ClearConsumers();
    fdds::Log::RegisterConsumer(std::make_unique<Consumer>());
    // Before the statics go (Fast DDS's log consumes what is left then, from its thread).
    std::atexit([] { state().exiting = true; });
  });
}

}  // namespace fastdds_log

/// Routes Fast DDS's log through spdlog (once per process) and counts, in
/// `bus`, the samples Fast DDS drops on its readers (see the top of this
/// file): its `subscribers` report what their readers lose or reject (the
/// readers made with fastDdsReaderMask()). `bus` has a participant;
/// detachFastDdsLog before it goes.
inline void attachFastDdsLog(Bus& bus,
                             std::initializer_list<eprosima::fastdds::dds::Subscriber*> subscribers) {
  fastdds_log::route();
  auto& s = fastdds_log::state();
  for (auto* subscriber : subscribers) {
    subscriber->set_listener(&s.drop_listener, fastdds_log::dropStatuses());
  }
  std::lock_guard lock(s.mutex);
  s.buses.push_back(&bus);
}

/// A reader's status mask: every status but those its subscriber reports
/// (DropListener), which no reader listener of the bus handles.
inline eprosima::fastdds::dds::StatusMask fastDdsReaderMask() {
  using eprosima::fastdds::dds::StatusMask;
  auto mask = StatusMask::all();
  mask >> StatusMask::sample_lost() >> StatusMask::sample_rejected();
  return mask;
}

inline void detachFastDdsLog(Bus& bus) {
  auto& s = fastdds_log::state();
  std::lock_guard lock(s.mutex);
  std::erase(s.buses, &bus);
  std::erase_if(s.type_of, [&](const auto& entry) { return entry.first.first == &bus; });
}

/// Samples Fast DDS rejected in this process for a payload larger than the
/// reader's type allows (every reader, every participant).
inline std::uint64_t fastDdsRejectedSamples() { return fastdds_log::state().rejected.load(); }

}  // namespace flatsat::bus
