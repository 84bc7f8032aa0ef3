// SPDX-License-Identifier: Apache-2.0
#include "components/device_sim/ReactionWheelDevice.hpp"

#include <cmath>

#include "components/common/Validation.hpp"

namespace flatsat::device_sim {

std::vector<std::string> ReactionWheelDeviceParams::validate() const {
  std::vector<std::string> e;
  if (wheel_count < 1 || wheel_count > 4) e.push_back("wheel_count: must be 1..4");
  for (int i = 0; i < wheel_count && i < 4; ++i) {
    if (!(inertia_kg_m2(i) > 0.0 && std::isfinite(inertia_kg_m2(i)))) {
      e.push_back("inertia_kg_m2: wheel " + std::to_string(i + 1) + " must be > 0");
    }
  }
  if (!(max_torque_Nm > 0.0 && max_torque_Nm <= 10.0)) e.push_back("max_torque_Nm: must be in (0, 10] N m");
  if (!(response_delay_s >= 0.0 && response_delay_s <= 10.0)) e.push_back("response_delay_s: must be in [0, 10] s");
  return e;
}

ReactionWheelDevice::ReactionWheelDevice(const Params& params)
    : params_(validated(params, "ReactionWheelDeviceParams")) {}

void ReactionWheelDevice::reset(const Eigen::Vector4d& speed_rad_s, double t_s) {
  pending_.clear();
  speed_ = speed_rad_s;
  for (int i = params_.wheel_count; i < 4; ++i) speed_(i) = 0.0;
  applied_.setZero();
  t_ = t_s;
}

bool ReactionWheelDevice::command(const Eigen::Vector4d& torque_Nm, double t_s) {
  if (!torque_Nm.allFinite()) return false;
  Eigen::Vector4d limited = torque_Nm.cwiseMax(-params_.max_torque_Nm).cwiseMin(params_.max_torque_Nm);
  for (int i = params_.wheel_count; i < 4; ++i) limited(i) = 0.0;
  pending_.emplace_back(std::max(t_s, t_) + params_.response_delay_s, limited);
  return true;
}

const Eigen::Vector4d& ReactionWheelDevice::step(double t_s) {
  const auto integrate = [&](double until) {
    for (int i = 0; until > t_ && i < params_.wheel_count; ++i) {
      speed_(i) += applied_(i) / params_.inertia_kg_m2(i) * (until - t_);
    }
    t_ = std::max(t_, until);
  };
  while (!pending_.empty() && pending_.front().first <= t_s) {
    integrate(pending_.front().first);
    applied_ = pending_.front().second;
    pending_.pop_front();
  }
  integrate(t_s);
  return speed_;
}

}  // namespace flatsat::device_sim
