// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "bus/Bus.hpp"
#include "bus/GuardedType.hpp"
#include "bus/LocalHub.hpp"
#include "bus/Qos.hpp"
#include "bus/Stamp.hpp"

namespace flatsat::bus {

/// Typed writer for one registry topic: a DDS DataWriter, or on an
/// in-process bus (composed rig) a writer of the hub's channel.
template <class Def>
class Writer {
 public:
  using Sample = typename Def::Type;

  Writer(Bus& bus, const Def& def) : name_(def.name) {
    if (LocalHub* hub = bus.localHub()) {
      local_ = &hub->channel(def);
      local_id_ = local_->addWriter();
      return;
    }
    publisher_ = &bus.publisher();
    auto& topic = bus.topic(std::string(def.name),
                            new GuardedType<typename Def::PubSubType>(bus.dropCounter()));
    writer_ = publisher_->create_datawriter(&topic, writerQos(def.qos, bus.tuning()));
    if (writer_ == nullptr) throw std::runtime_error("could not create a writer on " + name_);
  }
  ~Writer() {
    if (local_ != nullptr) local_->removeWriter(local_id_);
    else publisher_->delete_datawriter(writer_);
  }
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  void write(const Sample& sample) {
    writeOnce(sample);
    if (write_again_ && write_again_(sample)) writeOnce(sample);
  }
  /// Writes each sample for which `again` is true a second time (a bus
  /// duplicate fault, bus/BusFaults.hpp).
  void writeAgainWhen(std::function<bool(const Sample&)> again) { write_again_ = std::move(again); }
  /// Writes the last sample again (over DDS only: in-process delivery is
  /// never lost). Readers that hold it already drop the copy (bus::Input).
  void rewriteLast() {
    if (local_ == nullptr && last_) writeOnce(*last_);
  }
  int matchedReaders() const {
    if (local_ != nullptr) return local_->readers();
    eprosima::fastdds::dds::PublicationMatchedStatus status;
    writer_->get_publication_matched_status(status);
    return status.current_count;
  }
  /// Blocks until every matched reader acknowledged what was written
  /// (in-process: at once, a write returns once every reader has the sample).
  bool waitForAcknowledgments(std::chrono::milliseconds timeout) {
    if (local_ != nullptr) return true;
    return writer_->wait_for_acknowledgments(ddsDuration(timeout)) == ReturnCode_t::RETCODE_OK;
  }
  const std::string& topicName() const { return name_; }
  /// Tells readers this writer is alive (MANUAL_BY_TOPIC liveliness; in-process: nothing to tell).
  void assertLiveliness() {
    if (local_ == nullptr) writer_->assert_liveliness();
  }

 private:
  void writeOnce(const Sample& sample) {
    if (local_ != nullptr) {
      local_->write(local_id_, sample);
      return;
    }
    if (!writer_->write(const_cast<Sample*>(&sample))) {
      throw std::runtime_error("write failed on topic " + name_);
    }
    last_ = sample;
  }

  std::string name_;
  std::function<bool(const Sample&)> write_again_;
  std::optional<Sample> last_;  // for rewriteLast()
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
  LocalChannel<Def>* local_ = nullptr;
  std::size_t local_id_ = 0;
};

/// Whose samples a reader takes: writers of participants named in
/// `producers` (a rig's participants bear their component's name). Empty: any
/// writer's. Another writer is reported to `on_foreign` (on a Fast DDS
/// thread) as it matches and at each of its samples, which are dropped: with
/// the writer's GUID (empty after its first report: only the first names the
/// writer, so later refusals skip formatting it), its participant's
/// name ("" when unknown), whether it is the first report of that writer and
/// whether a sample was dropped.
struct WriterTrust {
  std::vector<std::string> producers;
  /// A topic every component writes (StepDone, health): a sample is taken
  /// only when its header.source names the writer's own participant (or the
  /// participant is one of `producers`, which may write for anyone).
  bool source_is_participant = false;
  std::function<void(const std::string& writer_guid, const std::string& participant, bool first, bool sample)>
      on_foreign;
};

/// When and from whom a sample came: what a watching reader (an operator
/// tool) hands over with each sample.
struct Arrival {
  std::chrono::steady_clock::time_point wall;  ///< when it was taken
  eprosima::fastrtps::rtps::GUID_t writer;
  /// Written before the reader subscribed: a transient-local topic's history,
  /// not part of the live stream (rates skip it).
  bool historical = false;
};

/// Typed reader for one registry topic; every valid sample is handed to a
/// callback on a Fast DDS thread. A sample that does not decode is dropped
/// and counted in the bus (GuardedType). On an in-process bus the callback
/// runs on the writer's thread, inside its write.
template <class Def>
class Reader : private eprosima::fastdds::dds::DataReaderListener {
 public:
  using Sample = typename Def::Type;
  using Callback = std::function<void(const Sample&)>;

  /// Called (on a Fast DDS thread) when a writer's liveliness is lost or
  /// regained, with the header.source of that writer's samples; writers that
  /// never delivered a sample are not reported, nor the loss of one whose
  /// source has another writer that delivered since (a restarted process).
  using LivelinessCallback = std::function<void(const std::string& source, bool alive)>;
  /// Called (on a Fast DDS thread) each time the topic's deadline QoS period
  /// (paced stepped topics: QosTuning::lease) passes without a sample, with the
  /// header.source of the last sample ("" before the first).
  using DeadlineCallback = std::function<void(const std::string& source)>;

  /// A watching reader's callback: every writer's samples, with their Arrival.
  using ArrivalCallback = std::function<void(const Sample&, const Arrival&)>;
  /// A watching reader's liveliness: a writer's lost (false) or regained (true), by its GUID.
  using WriterLivelinessCallback = std::function<void(const eprosima::fastrtps::rtps::GUID_t& writer, bool alive)>;

  /// A watching reader, as the operator tools read a rig (over DDS only): every
  /// writer's samples with their Arrival, on the watching QoS (watchingQos:
  /// stepped topics live and best-effort, so watching adds no protocol work).
  Reader(Bus& bus, const Def& def, ArrivalCallback on_sample, WriterLivelinessCallback on_liveliness = {})
      : name_(def.name),
        on_arrival_(std::move(on_sample)),
        on_writer_liveliness_(std::move(on_liveliness)),
        subscribed_ns_(std::chrono::duration_cast<std::chrono::nanoseconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count()) {
    if (bus.localHub() != nullptr) throw std::logic_error("a watching reader reads over DDS: " + name_);
    bus_ = &bus;
    auto& topic = bus.topic(std::string(def.name),
                            new GuardedType<typename Def::PubSubType>(bus.dropCounter()));
    reader_ = bus.createReader(topic, watchingQos(def.qos, static_cast<bool>(on_writer_liveliness_)), this);
  }

  /// `trust`: whose samples it takes (over DDS; in process every writer is the rig's own code).
  Reader(Bus& bus, const Def& def, Callback on_sample, LivelinessCallback on_liveliness = {},
         DeadlineCallback on_deadline = {}, WriterTrust trust = {})
      : name_(def.name),
        on_sample_(std::move(on_sample)),
        on_liveliness_(std::move(on_liveliness)),
        on_deadline_(std::move(on_deadline)),
        trust_(std::move(trust)) {
    if (LocalHub* hub = bus.localHub()) {
      local_ = &hub->channel(def);
      local_id_ = local_->addReader(&on_sample_);
      return;
    }
    bus_ = &bus;
    auto& topic = bus.topic(std::string(def.name),
                            new GuardedType<typename Def::PubSubType>(bus.dropCounter()));
    reader_ =
        bus.createReader(topic, readerQos(def.qos, bus.tuning(), static_cast<bool>(on_liveliness_)), this);
  }
  ~Reader() {
    if (local_ != nullptr) {
      local_->removeReader(local_id_);
      return;
    }
    reader_->set_listener(nullptr);
    bus_->deleteReader(reader_);
  }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  int matchedWriters() const {
    if (local_ != nullptr) return local_->writers();
    eprosima::fastdds::dds::SubscriptionMatchedStatus status;
    reader_->get_subscription_matched_status(status);
    return status.current_count;
  }
  const std::string& topicName() const { return name_; }
  /// Whether a writer of one of `participants` is matched (in process: any writer,
  /// as every one is the rig's own code). Matched writers are counted, not named,
  /// by Fast DDS's own status; get_matched_publications is unsupported in 2.9.
  bool matchedFrom(const std::vector<std::string>& participants) const {
    if (local_ != nullptr) return local_->writers() > 0;
    std::lock_guard lock(trust_mutex_);
    for (const auto& writer : matched_) {
      const auto name = participantOf(writer);
      if (name && std::find(participants.begin(), participants.end(), *name) != participants.end()) return true;
    }
    return false;
  }

  /// Requests a longer deadline than the QoS preset's (a producer slower than the
  /// lease); the writers' offered one stays compatible. Nothing in process.
  void requestDeadline(std::chrono::nanoseconds period) {
    if (reader_ == nullptr) return;
    auto qos = reader_->get_qos();
    qos.deadline().period = ddsDuration(period);
    reader_->set_qos(qos);
  }

 private:
  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override {
    Sample sample;
    eprosima::fastdds::dds::SampleInfo info;
    while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (on_arrival_) {
        if (info.valid_data) {
          on_arrival_(sample, {std::chrono::steady_clock::now(), info.sample_identity.writer_guid(),
                               info.source_timestamp.to_ns() < subscribed_ns_});
        }
        continue;
      }
      if (!info.valid_data || !trusted(info.publication_handle, sample.header())) continue;
      if (on_liveliness_ || on_deadline_) {
        std::lock_guard lock(sources_mutex_);
        last_source_ = text(sample.header().source());
        if (on_liveliness_) sources_[info.publication_handle] = last_source_;
      }
      on_sample_(sample);
    }
  }
  void on_liveliness_changed(eprosima::fastdds::dds::DataReader*,
                             const eprosima::fastdds::dds::LivelinessChangedStatus& status) override {
    if (on_writer_liveliness_) {
      eprosima::fastrtps::rtps::GUID_t writer;
      eprosima::fastrtps::rtps::iHandle2GUID(writer, status.last_publication_handle);
      if (status.not_alive_count_change > 0) on_writer_liveliness_(writer, false);
      if (status.alive_count_change > 0) on_writer_liveliness_(writer, true);
      return;
    }
    if (!on_liveliness_) return;
    std::string source;
    bool another_writer = false;  // of the same source: a restarted process that came back first
    {
      std::lock_guard lock(sources_mutex_);
      const auto it = sources_.find(status.last_publication_handle);
      if (it == sources_.end()) return;
      source = it->second;
      if (status.not_alive_count_change > 0) {
        sources_.erase(it);
        for (const auto& [handle, other] : sources_) another_writer |= other == source;
      }
    }
    if (status.not_alive_count_change > 0 && !another_writer) on_liveliness_(source, false);
    if (status.alive_count_change > 0) on_liveliness_(source, true);
  }

  void on_requested_deadline_missed(eprosima::fastdds::dds::DataReader*,
                                    const eprosima::fastdds::dds::RequestedDeadlineMissedStatus&) override {
    if (!on_deadline_) return;
    std::string source;
    {
      std::lock_guard lock(sources_mutex_);
      source = last_source_;
    }
    on_deadline_(source);
  }

  /// A writer that is not a producer's is named as it matches, before it
  /// writes: exclusive ownership drops the samples of a weaker one before
  /// they could be taken, so on_data_available would never see it.
  void on_subscription_matched(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::SubscriptionMatchedStatus& status) override {
    {
      std::lock_guard lock(trust_mutex_);
      if (status.current_count_change > 0) {
        matched_.insert(status.last_publication_handle);
      } else if (status.current_count_change < 0) {
        matched_.erase(status.last_publication_handle);
      }
    }
    if (status.current_count_change <= 0 || trust_.producers.empty() || trust_.source_is_participant) return;
    std::string participant;
    {
      std::lock_guard lock(trust_mutex_);
      WriterSeen* seen = judged(status.last_publication_handle);
      if (seen == nullptr || seen->trusted || std::exchange(seen->reported, true)) return;
      participant = seen->participant;
    }
    foreign(status.last_publication_handle, participant, true, false);
  }

  /// Whether the writer's samples are taken (WriterTrust); tells on_foreign of each one that is not.
  bool trusted(const eprosima::fastdds::dds::InstanceHandle_t& writer, const msg::SampleHeader& header) {
    if (trust_.producers.empty() && !trust_.source_is_participant) return true;
    bool first = false;
    std::string participant;
    {
      std::lock_guard lock(trust_mutex_);
      if (WriterSeen* seen = judged(writer)) {
        participant = seen->participant;
        if (seen->trusted &&
            (!trust_.source_is_participant || seen->any_source || text(header.source()) == participant)) {
          return true;
        }
        first = !std::exchange(seen->reported, true);
      }
    }
    foreign(writer, participant, first, true);
    return false;
  }

  struct WriterSeen {
    bool trusted = false;      ///< a producer's (or, source_is_participant, any participant's)
    std::string participant;   ///< its participant's name
    bool reported = false;     ///< on_foreign was told of it
    bool any_source = false;   ///< source_is_participant: one of `producers`, which may name any source
  };

  /// What is known of `writer`, judged at its first match or sample; nullptr
  /// while its participant's name is unknown. A participant's name is known
  /// before its writers match (discovery's order), so a nameless one is gone
  /// already: judged again if it comes back. With trust_mutex_ held.
  WriterSeen* judged(const eprosima::fastdds::dds::InstanceHandle_t& writer) {
    if (const auto it = writer_trusted_.find(writer); it != writer_trusted_.end()) return &it->second;
    const auto name = participantOf(writer);
    if (!name) return nullptr;
    const bool producer =
        std::find(trust_.producers.begin(), trust_.producers.end(), *name) != trust_.producers.end();
    return &writer_trusted_.emplace(writer, WriterSeen{trust_.source_is_participant || producer, *name, false, producer})
                .first->second;
  }

  /// The name of `writer`'s participant; none while discovery has not announced it.
  std::optional<std::string> participantOf(const eprosima::fastdds::dds::InstanceHandle_t& writer) const {
    eprosima::fastrtps::rtps::GUID_t guid;
    eprosima::fastrtps::rtps::iHandle2GUID(guid, writer);
    return bus_->participantName(guid.guidPrefix);
  }

  void foreign(const eprosima::fastdds::dds::InstanceHandle_t& writer, const std::string& participant, bool first,
               bool sample) {
    if (!trust_.on_foreign) return;
    if (!first) return trust_.on_foreign({}, participant, false, sample);  // counted only: its GUID was told
    eprosima::fastrtps::rtps::GUID_t guid;
    eprosima::fastrtps::rtps::iHandle2GUID(guid, writer);
    std::ostringstream text;
    text << guid;
    trust_.on_foreign(text.str(), participant, first, sample);
  }

  std::string name_;
  Callback on_sample_;
  ArrivalCallback on_arrival_;                      // a watching reader's
  WriterLivelinessCallback on_writer_liveliness_;   // a watching reader's
  std::int64_t subscribed_ns_ = 0;                  // [ns] system clock, as the writers' source timestamps
  LivelinessCallback on_liveliness_;
  DeadlineCallback on_deadline_;
  WriterTrust trust_;
  mutable std::mutex trust_mutex_;
  std::map<eprosima::fastdds::dds::InstanceHandle_t, WriterSeen> writer_trusted_;  // judged()
  std::set<eprosima::fastdds::dds::InstanceHandle_t> matched_;                      // matchedFrom()
  std::mutex sources_mutex_;
  std::string last_source_;
  std::map<eprosima::fastdds::dds::InstanceHandle_t, std::string> sources_;  // writer -> header.source
  Bus* bus_ = nullptr;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
  LocalChannel<Def>* local_ = nullptr;
  std::size_t local_id_ = 0;
};

/// Endpoint types of a registry topic: WriterOf<topics::kTruth>, ...
template <const auto& Topic>
using WriterOf = Writer<std::remove_cvref_t<decltype(Topic)>>;
template <const auto& Topic>
using ReaderOf = Reader<std::remove_cvref_t<decltype(Topic)>>;

}  // namespace flatsat::bus
