// SPDX-License-Identifier: Apache-2.0
#include "sim/Disturbances.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace flatsat::sim {

Eigen::Vector3d gravityGradientTorque_B_Nm(const Eigen::Vector3d& r_B_m, const Eigen::Matrix3d& J_B, double mu) {
  const double r2 = r_B_m.squaredNorm();
  return (3.0 * mu / (r2 * r2 * std::sqrt(r2))) * r_B_m.cross(J_B * r_B_m);
}

}  // namespace flatsat::sim
