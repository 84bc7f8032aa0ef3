// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <Eigen/Core>

#include "sim/Constants.hpp"

namespace flatsat::sim {

/// [N m] Gravity-gradient torque of a point-mass Earth on a rigid body,
/// 3μ/|r|⁵ (r × J r) (Markley & Crassidis, Fundamentals of Spacecraft Attitude
/// Determination and Control, Eq. 3.155; Wertz, Spacecraft Attitude Determination
/// and Control, pp. 566–570). First order in body size / |r|.
/// @param r_B_m [m] spacecraft position from the Earth's centre, body axes.
/// @param J_B [kg m²] inertia about the centre of mass, body axes.
Eigen::Vector3d gravityGradientTorque_B_Nm(const Eigen::Vector3d& r_B_m, const Eigen::Matrix3d& J_B,
                                           double mu = kMuEarth_m3_s2);

}  // namespace flatsat::sim
