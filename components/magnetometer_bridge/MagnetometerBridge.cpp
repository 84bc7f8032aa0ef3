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

MagnetometerBridge::MagnetometerBridge(const Params& params)
    : params_(validated(params, "MagnetometerBridgeParams")) {}

void MagnetometerBridge::reset() { has_last_ = false; }

MagnetometerBridgeOutput MagnetometerBridge::step(const FieldSample& sample) {
  MagnetometerBridgeOutput out;
  Eigen::Vector3d b_S_T;
  for (int i = 0; i < 3; ++i) b_S_T[i] = static_cast<double>(sample.b_nT[i]) * 1e-9;
  out.saturated = (b_S_T.cwiseAbs().array() >= params_.range_T).any();
  out.b_B_T = params_.q_body_sensor * b_S_T;
  // Unsigned arithmetic: a wrap of the 32-bit counter is not a gap.
  if (has_last_) out.missed_samples = sample.sequence - last_sequence_ - 1;
  has_last_ = true;
  last_sequence_ = sample.sequence;
  return out;
}

FieldSample deviceSample(const Eigen::Vector3d& b_B_T, const MagnetometerBridgeParams& mounting,
                         std::uint32_t sequence) {
  const Eigen::Vector3d b_S_T = mounting.q_body_sensor.conjugate() * b_B_T;
  FieldSample s;
  s.sequence = sequence;
  for (int i = 0; i < 3; ++i) {
    const double clipped = std::clamp(b_S_T[i], -mounting.range_T, mounting.range_T);
    s.b_nT[i] = static_cast<std::int32_t>(std::lround(clipped * 1e9));
  }
  return s;
}

}  // namespace flatsat::magnetometer_bridge
