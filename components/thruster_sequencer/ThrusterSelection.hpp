// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sim/Thrusters.hpp"

namespace flatsat::thruster_sequencer {

/// Which thrusters fire, and how long relative to each other, for one torque direction.
struct ThrusterFiring {
  sim::ThrusterVector weight = sim::ThrusterVector::Zero();  // [-] on-time fraction per thruster, max 1; 0: off
  Eigen::Vector3d torque_B_Nm = Eigen::Vector3d::Zero();     // [N m] all fire for `weight` of the time
  Eigen::Vector3d force_B_N = Eigen::Vector3d::Zero();       // [N] the net force meanwhile (0: a pure couple)
  bool possible() const { return weight.maxCoeff() > 0.0; }
};

/// Thruster selection by non-negative least squares over the thruster table: minimise
/// |T x − u|² + |F x / L|² over on-time fractions x ≥ 0 (Lawson & Hanson, Solving Least
/// Squares Problems, 1974, ch. 23, algorithm NNLS), T and F the torque and force columns of
/// the live thrusters at zero gimbal angles, u the unit torque direction, L [m] the length
/// that weighs force against torque. Where two or more thrusters form a couple about u the
/// optimum has zero net force (the pairs of a reaction control system); otherwise the least
/// force the geometry allows. Failed thrusters get no column. x is scaled so its largest
/// entry is 1: the strongest firing in that direction.
ThrusterFiring selectThrusters(const std::vector<sim::ThrusterParams>& thrusters,
                               const Eigen::Vector3d& torque_direction_B, double force_weight_m);

}  // namespace flatsat::thruster_sequencer
