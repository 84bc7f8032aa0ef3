// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "components/magnetometer_bridge/MagnetometerFrame.hpp"

namespace flatsat::magnetometer_bridge {

/// How the device is mounted and what it can measure.
struct MagnetometerBridgeParams {
  /// [-] rotation taking sensor axes to body axes (the mounting calibration), unit
  Eigen::Quaterniond q_body_sensor = Eigen::Quaterniond::Identity();
  double range_T = 100e-6;  // [T] per-axis full scale of the device, > 0

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct MagnetometerBridgeOutput {
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();  // [T] body axes
  bool saturated = false;             // an axis at or beyond full scale
  std::uint32_t missed_samples = 0;   // sequence numbers skipped before this one
};

/// The device's frames as the rig's magnetometer reading: nT in sensor axes to
/// tesla in body axes; a sequence gap (frames lost on the line) is counted.
class MagnetometerBridge {
 public:
  using Params = MagnetometerBridgeParams;
  explicit MagnetometerBridge(const Params& params);
  void reset();
  MagnetometerBridgeOutput step(const FieldSample& sample);

 private:
  Params params_;
  bool has_last_ = false;
  std::uint32_t last_sequence_ = 0;
};

/// The device end: the field in body axes as the device's frame (sensor axes,
/// whole nanotesla, clipped at full scale). Used by the device simulator.
FieldSample deviceSample(const Eigen::Vector3d& b_B_T, const MagnetometerBridgeParams& mounting,
                         std::uint32_t sequence);

}  // namespace flatsat::magnetometer_bridge
