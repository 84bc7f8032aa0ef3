// SPDX-License-Identifier: Apache-2.0
#pragma once
// The topic type the bus registers for every registry topic: the generated
// PubSubType with a deserialize() that never throws and reports every
// payload that does not decode.
//
// Why: fastddsgen 2.3.0 (Debian's) wraps the decoding of a sample in
// `catch (NotEnoughMemoryException&)` only. A payload with a bad
// encapsulation header makes Cdr::read_encapsulation() throw
// BadParamException, which escapes through DataReader::take_next_sample()
// into the Fast DDS thread that runs the listener and std::terminate()s the
// process: one rogue sample on a topic would abort every subscriber. Fast DDS
// 2.9.1 skips a sample whose deserialize() returns false (it reaches no
// listener; tests/component/MalformedSamplesNodeTest.cpp), so the drop is
// counted here, where it happens.
#include <functional>

#include <fastdds/dds/topic/TopicDataType.hpp>

namespace flatsat::bus {

template <class PubSub>
class GuardedType final : public PubSub {
 public:
  /// `on_drop(type name)` runs, on the decoding thread, for every payload
  /// that does not decode.
  explicit GuardedType(std::function<void(const char*)> on_drop = {})
      : on_drop_(std::move(on_drop)) {}

  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    bool ok = false;
    try {
      ok = PubSub::deserialize(payload, data);
    } catch (...) {  // any fastcdr exception, std::bad_alloc, ...: the sample is dropped
      ok = false;
    }
    if (!ok && on_drop_) on_drop_(this->getName());
    return ok;
  }

 private:
  std::function<void(const char*)> on_drop_;
};

}  // namespace flatsat::bus
