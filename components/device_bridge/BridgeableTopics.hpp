// SPDX-License-Identifier: Apache-2.0
#pragma once
// What a device description may name as its topic: a stepped topic of the registry
// with a producer, which a `<producer>_bridge` may write over at the bridge strength
// (bus::Node::trustFor). Its fields are the leaves of its IDL type (msg::leafFields).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bus/Topics.hpp"
#include "msg/MsgJson.hpp"

namespace flatsat::device_bridge {

/// Calls f(def) for registry topic `name` when a bridge may publish it; false when none.
template <class F>
bool withBridgeableTopic(std::string_view name, F&& f) {
  bool found = false;
  bus::forEachTopic([&](const auto& def) {
    if (found || def.name != name || def.qos != bus::QosKind::kStepped || def.producer.empty()) return;
    found = true;
    f(def);
  });
  return found;
}

/// The leaves of a bridgeable topic ("b_body_T[0]", "valid"), which live as long as the
/// program; nullptr for any other topic.
inline const std::vector<msg::FieldInfo>* bridgeableLeaves(std::string_view topic) {
  const std::vector<msg::FieldInfo>* leaves = nullptr;
  withBridgeableTopic(topic, [&](const auto& def) { leaves = &msg::leafFields<typename std::remove_cvref_t<decltype(def)>::Type>(); });
  return leaves;
}

/// The unit of field `field` of a bridgeable topic, as its IDL gives it ("T" for
/// "b_body_T[0]"); nullopt when the topic is not bridgeable or has no such field
/// (device_protocol::FieldUnitLookup).
inline std::optional<std::string> bridgeableFieldUnit(const std::string& topic, const std::string& field) {
  const auto* leaves = bridgeableLeaves(topic);
  for (std::size_t i = 0; leaves != nullptr && i < leaves->size(); ++i) {
    if ((*leaves)[i].name == field) return std::string((*leaves)[i].unit);
  }
  return std::nullopt;
}

/// The producer of a bridgeable topic ("magnetometer"); empty for any other.
inline std::string bridgeableProducer(std::string_view topic) {
  std::string producer;
  withBridgeableTopic(topic, [&](const auto& def) { producer = def.producer; });
  return producer;
}

/// The command topic an actuator bridge `<producer>_bridge` may take and write to its
/// device as command frames, with what the device reports published as `producer`'s
/// topic: a reaction wheel takes the controller's wheel torques and reports its speeds
/// as the tachometers do. Empty: `producer`'s device is a sensor only.
inline std::string actuatorCommandTopic(std::string_view producer) {
  if (producer == bus::topics::kWheelTach.producer) return std::string(bus::topics::kWheelTorqueCmd.name);
  return {};
}

}  // namespace flatsat::device_bridge
