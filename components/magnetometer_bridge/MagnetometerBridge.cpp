// SPDX-License-Identifier: Apache-2.0
#include "components/magnetometer_bridge/MagnetometerBridge.hpp"

#include <algorithm>
#include <cmath>

#include "components/common/Validation.hpp"

namespace flatsat::magnetometer_bridge {

std::vector<std::string> MagnetometerBridgeParams::validate() const {
  std::vector<std::string> e;
  requireUnit(e, "q_body_sensor", q_body_sensor.coeffs());
  requirePositive(e, "range_T", range_T);
  return e;
}

std::optional<MagnetometerFields> MagnetometerFields::of(const device_protocol::FrameSpec& frame, std::string& why) {
  MagnetometerFields fields;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string leaf = "b_body_T[" + std::to_string(i) + "]";
    const auto index = frame.fieldFor(leaf);
    if (!index) {
      why = "no field of frame '" + frame.name + "' carries " + leaf;
      return std::nullopt;
    }
    fields.axis[i] = *index;
    fields.scale_T[i] = frame.fields[*index].scale;
  }
  fields.sequence = frame.sequenceField();
  if (fields.sequence) {
    fields.sequence_modulus = std::uint64_t{1} << (8 * device_protocol::fieldBytes(frame.fields[*fields.sequence].type));
  }
  return fields;
}

MagnetometerBridge::MagnetometerBridge(const Params& params, const MagnetometerFields& fields)
    : params_(validated(params, "MagnetometerBridgeParams")), fields_(fields) {}

void MagnetometerBridge::reset() { has_last_ = false; }

MagnetometerBridgeOutput MagnetometerBridge::step(const device_protocol::RawValues& frame) {
  MagnetometerBridgeOutput out;
  Eigen::Vector3d b_S_T;
  for (std::size_t i = 0; i < 3; ++i) b_S_T[static_cast<Eigen::Index>(i)] = frame[fields_.axis[i]] * fields_.scale_T[i];
  out.saturated = (b_S_T.cwiseAbs().array() >= params_.range_T).any();
  out.b_B_T = params_.q_body_sensor * b_S_T;
  if (fields_.sequence) {
    // An unsigned counter (FrameSpec::validate): its wrap is not a gap.
    const auto sequence = static_cast<std::uint64_t>(frame[*fields_.sequence]);
    const std::uint64_t m = fields_.sequence_modulus;
    if (has_last_) out.missed_samples = (sequence + 2 * m - last_sequence_ - 1) % m;
    has_last_ = true;
    last_sequence_ = sequence;
  }
  return out;
}

device_protocol::RawValues deviceFrame(const Eigen::Vector3d& b_B_T, const MagnetometerBridgeParams& mounting,
                                       const device_protocol::FrameSpec& frame, const MagnetometerFields& fields,
                                       std::uint64_t sequence) {
  const Eigen::Vector3d b_S_T = mounting.q_body_sensor.conjugate() * b_B_T;
  device_protocol::RawValues raw(frame.fields.size(), 0.0);
  for (std::size_t i = 0; i < 3; ++i) {
    const double clipped = std::clamp(b_S_T[static_cast<Eigen::Index>(i)], -mounting.range_T, mounting.range_T);
    raw[fields.axis[i]] = clipped / fields.scale_T[i];  // encodeFrame rounds an integer field
  }
  if (fields.sequence) raw[*fields.sequence] = static_cast<double>(sequence % fields.sequence_modulus);
  return raw;
}

}  // namespace flatsat::magnetometer_bridge
