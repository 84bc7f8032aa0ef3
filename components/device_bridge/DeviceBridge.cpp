// SPDX-License-Identifier: Apache-2.0
#include "components/device_bridge/DeviceBridge.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "components/common/Validation.hpp"

namespace flatsat::device_bridge {
namespace {

/// "w_body_rad_s[1]" → ("w_body_rad_s", 1) for a component of a body-axes vector (the
/// topics' naming: <quantity>_body_<unit>); nullopt for any other leaf.
std::optional<std::pair<std::string, std::size_t>> bodyComponent(const std::string& leaf) {
  const auto open = leaf.rfind('[');
  if (open == std::string::npos || leaf.size() != open + 3 || leaf.back() != ']') return std::nullopt;
  const char digit = leaf[open + 1];
  const std::string base = leaf.substr(0, open);
  if (digit < '0' || digit > '2' || base.find("_body_") == std::string::npos) return std::nullopt;
  return std::make_pair(base, static_cast<std::size_t>(digit - '0'));
}

}  // namespace

std::vector<std::string> DeviceBridgeParams::validate() const {
  std::vector<std::string> e;
  requireUnit(e, "q_body_sensor", q_body_sensor.coeffs());
  return e;
}

std::optional<FrameMapping> FrameMapping::of(const device_protocol::FrameSpec& frame,
                                             const std::vector<std::string>& topic_leaves, std::string& why) {
  FrameMapping mapping;
  std::map<std::string, std::array<std::optional<std::size_t>, 3>> vectors;  // base → indices into leaves
  std::vector<bool> carried(topic_leaves.size(), false);
  for (std::size_t f = 0; f < frame.fields.size(); ++f) {
    const auto& field = frame.fields[f];
    if (field.maps_to.empty()) continue;
    const auto it = std::find(topic_leaves.begin(), topic_leaves.end(), field.maps_to);
    if (it == topic_leaves.end()) {
      why = "field '" + field.name + "' goes to '" + field.maps_to + "', which the topic does not have";
      return std::nullopt;
    }
    const auto leaf = static_cast<std::size_t>(it - topic_leaves.begin());
    if (carried[leaf]) {
      why = "two fields go to '" + field.maps_to + "'";
      return std::nullopt;
    }
    carried[leaf] = true;
    if (const auto component = bodyComponent(field.maps_to)) vectors[component->first][component->second] = mapping.leaves.size();
    mapping.leaves.push_back({f, leaf, field.scale, field.full_scale});
  }
  for (const auto& [base, xyz] : vectors) {
    // Turning a vector into body axes needs all of it: a component alone has no body axis.
    if (!xyz[0] || !xyz[1] || !xyz[2] || std::count(topic_leaves.begin(), topic_leaves.end(), base + "[3]") > 0) {
      why = "'" + base + "' is a body-axes vector: the frame must carry its three components (x, y, z)";
      return std::nullopt;
    }
    mapping.body_vectors.push_back({*xyz[0], *xyz[1], *xyz[2]});
  }
  const auto uncarried = [&](const std::string& name) -> std::optional<std::size_t> {
    const auto it = std::find(topic_leaves.begin(), topic_leaves.end(), name);
    if (it == topic_leaves.end() || carried[static_cast<std::size_t>(it - topic_leaves.begin())]) return std::nullopt;
    return static_cast<std::size_t>(it - topic_leaves.begin());
  };
  mapping.valid_leaf = uncarried("valid");
  mapping.saturated_leaf = uncarried("saturated");
  mapping.sequence = frame.sequenceField();
  if (mapping.sequence) {
    mapping.sequence_modulus = std::uint64_t{1} << (8 * device_protocol::fieldBytes(frame.fields[*mapping.sequence].type));
  }
  if (mapping.leaves.empty()) {
    why = "frame '" + frame.name + "' carries no field of the topic (no `to:`)";
    return std::nullopt;
  }
  return mapping;
}

DeviceBridge::DeviceBridge(const Params& params, FrameMapping mapping)
    : params_(validated(params, "DeviceBridgeParams")), mapping_(std::move(mapping)) {}

void DeviceBridge::reset() { has_last_ = false; }

BridgeSample DeviceBridge::step(const device_protocol::RawValues& frame) {
  BridgeSample out;
  std::vector<double> value(mapping_.leaves.size());
  for (std::size_t i = 0; i < mapping_.leaves.size(); ++i) {
    const auto& leaf = mapping_.leaves[i];
    value[i] = frame[leaf.field] * leaf.scale;
    // In the device's own axes, where its range applies.
    if (leaf.full_scale && std::abs(value[i]) >= *leaf.full_scale) out.saturated = true;
  }
  for (const auto& xyz : mapping_.body_vectors) {
    const Eigen::Vector3d body = params_.q_body_sensor * Eigen::Vector3d(value[xyz[0]], value[xyz[1]], value[xyz[2]]);
    for (std::size_t k = 0; k < 3; ++k) value[xyz[k]] = body[static_cast<Eigen::Index>(k)];
  }
  for (std::size_t i = 0; i < mapping_.leaves.size(); ++i) {
    out.finite = out.finite && std::isfinite(value[i]);
    out.leaves.emplace_back(mapping_.leaves[i].leaf, value[i]);
  }
  // A frame whose check passed is a measurement: the device would not send one otherwise.
  if (mapping_.valid_leaf) out.leaves.emplace_back(*mapping_.valid_leaf, 1.0);
  if (mapping_.saturated_leaf) out.leaves.emplace_back(*mapping_.saturated_leaf, out.saturated ? 1.0 : 0.0);
  if (mapping_.sequence) {
    // An unsigned counter (FrameSpec::validate): its wrap is not a gap.
    const auto sequence = static_cast<std::uint64_t>(frame[*mapping_.sequence]);
    const std::uint64_t m = mapping_.sequence_modulus;
    if (has_last_) out.missed_samples = (sequence + 2 * m - last_sequence_ - 1) % m;
    has_last_ = true;
    last_sequence_ = sequence;
  }
  return out;
}

device_protocol::RawValues deviceFrame(const std::vector<double>& topic_values, const DeviceBridgeParams& mounting,
                                       const device_protocol::FrameSpec& frame, const FrameMapping& mapping,
                                       std::uint64_t sequence) {
  std::vector<double> value(mapping.leaves.size());
  for (std::size_t i = 0; i < mapping.leaves.size(); ++i) value[i] = topic_values.at(mapping.leaves[i].leaf);
  for (const auto& xyz : mapping.body_vectors) {
    const Eigen::Vector3d sensor =
        mounting.q_body_sensor.conjugate() * Eigen::Vector3d(value[xyz[0]], value[xyz[1]], value[xyz[2]]);
    for (std::size_t k = 0; k < 3; ++k) value[xyz[k]] = sensor[static_cast<Eigen::Index>(k)];
  }
  device_protocol::RawValues raw(frame.fields.size(), 0.0);
  for (std::size_t i = 0; i < mapping.leaves.size(); ++i) {
    const auto& leaf = mapping.leaves[i];
    const double v = leaf.full_scale ? std::clamp(value[i], -*leaf.full_scale, *leaf.full_scale) : value[i];
    raw[leaf.field] = v / leaf.scale;  // encodeFrame rounds an integer field
  }
  if (mapping.sequence) raw[*mapping.sequence] = static_cast<double>(sequence % mapping.sequence_modulus);
  return raw;
}

}  // namespace flatsat::device_bridge
