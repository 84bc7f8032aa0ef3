// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "bus/GuardedType.hpp"

namespace flatsat::bus {

/// CDR bytes of a sample, as they travel on the wire (the recording format).
template <class Def>
std::vector<std::uint8_t> serialize(const typename Def::Type& sample) {
  typename Def::PubSubType type;
  auto* data = const_cast<typename Def::Type*>(&sample);
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(data)());
  if (!type.serialize(data, &payload)) {
    throw std::runtime_error("could not serialize a sample of " + std::string(type.getName()));
  }
  return {payload.data, payload.data + payload.length};
}

/// The sample of those bytes; throws std::runtime_error (never a decoder's
/// own exception) when they do not decode.
template <class Def>
typename Def::Type deserialize(const std::vector<std::uint8_t>& bytes) {
  GuardedType<typename Def::PubSubType> type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(bytes.size()));
  std::copy(bytes.begin(), bytes.end(), payload.data);
  payload.length = static_cast<std::uint32_t>(bytes.size());
  typename Def::Type sample;
  if (!type.deserialize(&payload, &sample)) {
    throw std::runtime_error("recorded payload does not decode as " +
                             std::string(type.getName()));
  }
  return sample;
}

}  // namespace flatsat::bus
