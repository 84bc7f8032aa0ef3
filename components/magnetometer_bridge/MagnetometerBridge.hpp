// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "components/device_protocol/FrameCodec.hpp"

namespace flatsat::magnetometer_bridge {

/// How the device is mounted and what it can measure.
struct MagnetometerBridgeParams {
  /// [-] rotation taking sensor axes to body axes (the mounting calibration), unit
  Eigen::Quaterniond q_body_sensor = Eigen::Quaterniond::Identity();
  double range_T = 100e-6;  // [T] per-axis full scale of the device, > 0

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// Where a magnetometer's frame (its device description) carries the field and its counter.
struct MagnetometerFields {
  std::array<std::size_t, 3> axis{};       // the fields of b_body_T[0..2], sensor axes on the wire
  std::array<double, 3> scale_T{};         // [T per count]
  std::optional<std::size_t> sequence;     // the sample counter, when the frame has one
  std::uint64_t sequence_modulus = 0;      // [-] its range: 2^(8 × its bytes)

  /// From a frame description; nullopt with `why` set when it does not carry all three axes.
  static std::optional<MagnetometerFields> of(const device_protocol::FrameSpec& frame, std::string& why);
};

struct MagnetometerBridgeOutput {
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();  // [T] body axes
  bool saturated = false;             // an axis at or beyond full scale
  std::uint64_t missed_samples = 0;   // sequence numbers skipped before this one
};

/// The device's frames as the rig's magnetometer reading: counts in sensor axes to tesla in
/// body axes; a sequence gap (frames lost on the line) is counted.
class MagnetometerBridge {
 public:
  using Params = MagnetometerBridgeParams;

  MagnetometerBridge(const Params& params, const MagnetometerFields& fields);

  void reset();
  /// One frame's values (device_protocol::FrameParser).
  MagnetometerBridgeOutput step(const device_protocol::RawValues& frame);

 private:
  Params params_;
  MagnetometerFields fields_;
  bool has_last_ = false;
  std::uint64_t last_sequence_ = 0;
};

/// The device end: the field in body axes as the device's frame values (sensor axes, in
/// counts, clipped at full scale; the counter modulo its range). Used by the device simulator.
device_protocol::RawValues deviceFrame(const Eigen::Vector3d& b_B_T, const MagnetometerBridgeParams& mounting,
                                       const device_protocol::FrameSpec& frame, const MagnetometerFields& fields,
                                       std::uint64_t sequence);

}  // namespace flatsat::magnetometer_bridge
