// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "bus/GuardedType.hpp"

namespace flatsat::bus {

/// CDR bytes of a sample, as they travel on the wire (the recording format),
/// into `bytes` (whose capacity is kept from call to call).
template <class Def>
void serializeInto(const typename Def::Type& sample, std::vector<std::uint8_t>& bytes) {
  // One type object and payload per thread: constructing them for each
  // sample (the type allocates and sizes itself, the payload allocates) was
  // most of what a recorded sample cost the step thread (callgrind).
  thread_local typename Def::PubSubType type;
  thread_local eprosima::fastrtps::rtps::SerializedPayload_t payload;
  auto* data = const_cast<typename Def::Type*>(&sample);
  const std::uint32_t size = type.getSerializedSizeProvider(data)();
  if (payload.max_size < size) payload.reserve(size);
  // CDR skips alignment padding without writing it: zeroed, as in a fresh
  // payload, so that no byte of an earlier sample reaches the recording.
  std::memset(payload.data, 0, size);
  if (!type.serialize(data, &payload)) {
    throw std::runtime_error("could not serialize a sample of " + std::string(type.getName()));
  }
  bytes.assign(payload.data, payload.data + payload.length);
}

template <class Def>
std::vector<std::uint8_t> serialize(const typename Def::Type& sample) {
  std::vector<std::uint8_t> bytes;
  serializeInto<Def>(sample, bytes);
  return bytes;
}

/// The sample of those bytes; throws std::runtime_error (never a decoder's
/// own exception) when they do not decode.
template <class Def>
typename Def::Type deserialize(const std::uint8_t* data, std::size_t size) {
  // One type and payload per thread, as in serializeInto(): a summary
  // decodes a sample of every recorded step.
  thread_local GuardedType<typename Def::PubSubType> type;
  thread_local eprosima::fastrtps::rtps::SerializedPayload_t payload;
  if (payload.max_size < size) payload.reserve(static_cast<std::uint32_t>(size));
  if (size > 0) std::memcpy(payload.data, data, size);
  payload.length = static_cast<std::uint32_t>(size);
  payload.pos = 0;
  typename Def::Type sample;
  if (!type.deserialize(&payload, &sample)) {
    throw std::runtime_error("recorded payload does not decode as " +
                             std::string(type.getName()));
  }
  return sample;
}

template <class Def>
typename Def::Type deserialize(const std::vector<std::uint8_t>& bytes) {
  return deserialize<Def>(bytes.data(), bytes.size());
}

}  // namespace flatsat::bus
