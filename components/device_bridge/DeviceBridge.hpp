// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "components/device_protocol/FrameCodec.hpp"

namespace flatsat::device_bridge {

/// How a device sits in the body.
struct DeviceBridgeParams {
  /// [-] rotation taking the device's axes to body axes (its mounting calibration), unit;
  /// identity for a device whose frames are in body axes already
  Eigen::Quaterniond q_body_sensor = Eigen::Quaterniond::Identity();

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// Where a device's frame carries its topic's fields. Topic fields are the leaves of the
/// topic's type in order (msg::leafFields: "b_body_T[0]", "valid").
struct FrameMapping {
  struct Leaf {
    std::size_t field = 0;              // index into FrameSpec::fields
    std::size_t leaf = 0;               // index into the topic's leaves
    double scale = 1.0;                 // [topic unit per count]
    std::optional<double> full_scale;   // [topic unit] the device's range, per component
  };
  std::vector<Leaf> leaves;             // every field the frame publishes
  /// Vectors in body axes (a leaf "<name>_body_<unit>[0..2]", three components): indices
  /// into `leaves` of x, y and z; on the wire they are in the device's axes.
  std::vector<std::array<std::size_t, 3>> body_vectors;
  std::optional<std::size_t> valid_leaf;      // the topic's `valid`, no field carries it: true for every good frame
  std::optional<std::size_t> saturated_leaf;  // the topic's `saturated`, no field carries it: a field at its full scale
  std::optional<std::size_t> sequence;        // the frame's sample counter
  std::uint64_t sequence_modulus = 0;         // [-] its range: 2^(8 × its bytes)

  /// The mapping of `frame` onto a topic with leaves `topic_leaves`; nullopt with `why` set
  /// when a field names no leaf, a leaf is carried twice, or a body vector only in part.
  static std::optional<FrameMapping> of(const device_protocol::FrameSpec& frame,
                                        const std::vector<std::string>& topic_leaves, std::string& why);
};

/// One frame as topic fields.
struct BridgeSample {
  std::vector<std::pair<std::size_t, double>> leaves;  // (topic leaf, value in its unit; vectors in body axes)
  bool saturated = false;             // a field at or beyond its full scale
  std::uint64_t missed_samples = 0;   // sequence numbers skipped before this one
  bool finite = true;                 // every value finite: an f64 count times its scale may overflow
};

/// A device's frames as its topic's samples (architecture, "Hardware swap-in"): counts to
/// the topic's units, the device's axes to body axes, a sequence gap (frames lost on the
/// line) counted. Generic over the topic: the description says which field goes where.
class DeviceBridge {
 public:
  using Params = DeviceBridgeParams;

  DeviceBridge(const Params& params, FrameMapping mapping);

  void reset();
  /// One frame's values (device_protocol::FrameParser).
  BridgeSample step(const device_protocol::RawValues& frame);

 private:
  Params params_;
  FrameMapping mapping_;
  bool has_last_ = false;
  std::uint64_t last_sequence_ = 0;
};

/// The device end (the device simulator): the topic's leaf values as an ideal device would
/// measure them (vectors in body axes) as the frame's values: in the device's axes, clipped
/// at full scale, in counts (encodeFrame rounds integers), the counter modulo its range.
device_protocol::RawValues deviceFrame(const std::vector<double>& topic_values, const DeviceBridgeParams& mounting,
                                       const device_protocol::FrameSpec& frame, const FrameMapping& mapping,
                                       std::uint64_t sequence);

}  // namespace flatsat::device_bridge
