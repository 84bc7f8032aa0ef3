// SPDX-License-Identifier: Apache-2.0
#include "components/thruster_sequencer/GimbalDumping.hpp"

#include <algorithm>

#include <Eigen/Geometry>
#include <Eigen/QR>

#include "components/common/Validation.hpp"

namespace flatsat::thruster_sequencer {

std::vector<std::string> GimbalDumpingParams::validate() const {
  std::vector<std::string> problems = wheels.validate("wheels");
  if (thrusters.size() > static_cast<std::size_t>(sim::kMaxThrusters)) {
    problems.push_back("thrusters: more than " + std::to_string(sim::kMaxThrusters));
  }
  if (!(dump_time_s >= 60.0 && dump_time_s <= 864000.0)) problems.push_back("dump_time_s: outside [60, 864000] s");
  return problems;
}

GimbalDumping::GimbalDumping(const GimbalDumpingParams& params) : params_(validated(params, "gimbal dumping")) {}

sim::ThrusterGimbals GimbalDumping::angles(const sim::ThrusterVector& on_time_s, const sim::ThrusterVector& dump_left_s,
                                           const Eigen::Vector4d& wheel_speed_rad_s, double step_s) const {
  sim::ThrusterGimbals out = sim::ThrusterGimbals::Zero();
  std::vector<int> used;
  Eigen::Matrix<double, 3, Eigen::Dynamic> torque_per_rad(3, 0);  // [N m/rad], the step's mean
  double left_s = 0.0;
  for (int i = 0; i < static_cast<int>(params_.thrusters.size()); ++i) {
    const sim::ThrusterParams& t = params_.thrusters[static_cast<std::size_t>(i)];
    if (!t.gimballed || !(dump_left_s(i) > 0.0) || on_time_s(i) <= 0.0) continue;
    left_s = std::max(left_s, dump_left_s(i));
    const double share = t.thrust_N * std::min(1.0, on_time_s(i) / step_s);
    torque_per_rad.conservativeResize(Eigen::NoChange, torque_per_rad.cols() + 2);
    torque_per_rad.col(torque_per_rad.cols() - 2) = share * t.r_B_m.cross(t.gimbal_axis1_B.cross(t.direction_B));
    torque_per_rad.col(torque_per_rad.cols() - 1) = share * t.r_B_m.cross(t.gimbal_axis2_B.cross(t.direction_B));
    used.push_back(i);
  }
  if (used.empty()) return out;
  const Eigen::Vector3d wanted_Nm =
      -params_.wheels.momentum_B_Nms(wheel_speed_rad_s) / std::min(params_.dump_time_s, std::max(left_s, step_s));
  const Eigen::VectorXd theta = torque_per_rad.completeOrthogonalDecomposition().solve(wanted_Nm);
  for (std::size_t k = 0; k < used.size(); ++k) {
    const sim::ThrusterParams& t = params_.thrusters[static_cast<std::size_t>(used[k])];
    for (int axis = 0; axis < 2; ++axis) {
      out(axis, used[k]) = std::clamp(theta(2 * static_cast<Eigen::Index>(k) + axis), t.gimbal_min_rad(axis),
                                      t.gimbal_max_rad(axis));
    }
  }
  return out;
}

}  // namespace flatsat::thruster_sequencer
