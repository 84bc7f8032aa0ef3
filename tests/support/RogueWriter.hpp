// SPDX-License-Identifier: Apache-2.0
#pragma once
// A rogue DDS writer: publishes arbitrary bytes as samples of a registry
// topic, under the topic's own type name and QoS, so every reader of the rig
// matches it and has to decode what it sends.
#include <chrono>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include "bus/Bus.hpp"
#include "bus/Qos.hpp"

namespace flatsat::test {

using Bytes = std::vector<std::uint8_t>;

/// A topic type whose "sample" is its serialized payload, verbatim.
class RawType final : public eprosima::fastdds::dds::TopicDataType {
 public:
  static constexpr std::uint32_t kMaxBytes = 1024;
  explicit RawType(const std::string& type_name) {
    setName(type_name.c_str());
    m_typeSize = kMaxBytes;
    m_isGetKeyDefined = false;
  }
  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override {
    const auto& bytes = *static_cast<const Bytes*>(data);
    if (bytes.size() > payload->max_size) return false;
    std::memcpy(payload->data, bytes.data(), bytes.size());
    payload->length = static_cast<std::uint32_t>(bytes.size());
    return true;
  }
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    auto& bytes = *static_cast<Bytes*>(data);
    bytes.assign(payload->data, payload->data + payload->length);
    return true;
  }
  std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override {
    const auto size = static_cast<std::uint32_t>(static_cast<const Bytes*>(data)->size());
    return [size] { return size; };
  }
  void* createData() override { return new Bytes(); }
  void deleteData(void* data) override { delete static_cast<Bytes*>(data); }
  bool getKey(void*, eprosima::fastrtps::rtps::InstanceHandle_t*, bool) override { return false; }
};

/// Payloads that no topic type decodes, each a different failure of the
/// generated deserialisers (fastcdr 1.0 Cdr::read_encapsulation, Cdr::read*):
inline std::vector<Bytes> malformedPayloads() {
  return {
      {0x01, 0x01, 0x00, 0x00},                    // non-zero first byte: BadParamException
      {0x00, 0x07, 0x00, 0x00},                    // unknown CDR kind: BadParamException
      {0x00, 0x01, 0x00, 0x00, 0x05, 0x00, 0x00},  // header cut after 3 bytes: NotEnoughMemory
  };
}

/// One writer of raw bytes on a registry topic, with that topic's QoS but
/// ownership strength 0, below every real producer: on exclusive-ownership
/// (stepped) topics readers take its samples only until the producer's first
/// one (an equal strength would take the topic over and starve the readers).
class RogueWriter {
 public:
  template <class Def>
  RogueWriter(bus::Bus& bus, const Def& def, bus::QosTuning tuning = {})
      : name_(def.name), publisher_(bus.publisher()) {
    typename Def::PubSubType real;
    auto& topic = bus.topic(name_, new RawType(real.getName()));
    tuning.ownership_strength = 0;
    writer_ = publisher_.create_datawriter(&topic, bus::writerQos(def.qos, tuning));
    if (writer_ == nullptr) throw std::runtime_error("rogue: no writer on " + name_);
  }
  ~RogueWriter() { publisher_.delete_datawriter(writer_); }
  RogueWriter(const RogueWriter&) = delete;
  RogueWriter& operator=(const RogueWriter&) = delete;

  void write(const Bytes& bytes) {
    if (!writer_->write(const_cast<Bytes*>(&bytes))) throw std::runtime_error("rogue: write failed on " + name_);
  }
  int matchedReaders() const {
    eprosima::fastdds::dds::PublicationMatchedStatus status;
    writer_->get_publication_matched_status(status);
    return status.current_count;
  }
  /// Waits (up to `timeout`) for at least `readers` matched readers.
  bool waitForReaders(int readers, std::chrono::milliseconds timeout) const {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (matchedReaders() < readers) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
  }
  bool waitForAcknowledgments(std::chrono::seconds timeout) {
    return writer_->wait_for_acknowledgments({static_cast<std::int32_t>(timeout.count()), 0}) ==
           ReturnCode_t::RETCODE_OK;
  }
  const std::string& topicName() const { return name_; }

 private:
  std::string name_;
  eprosima::fastdds::dds::Publisher& publisher_;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
};

}  // namespace flatsat::test
