// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace flatsat::sim {

/// Cross-product matrix: skew(a) * b == a.cross(b).
Eigen::Matrix3d skew(const Eigen::Vector3d& a);

/// Frame rotation by `angle_rad` about z (Vallado's ROT3): coordinates in the
/// rotated frame = rot3(angle) * coordinates in the original one.
Eigen::Matrix3d rot3(double angle_rad);

/// Exponential map: rotation by |phi| [rad] about phi / |phi| (unit quaternion).
Eigen::Quaterniond quatFromRotationVector(const Eigen::Vector3d& phi);

/// Logarithmic map [rad]: the rotation vector of q, |result| ≤ π (shortest rotation).
Eigen::Vector3d rotationVectorFromQuat(const Eigen::Quaterniond& q);

/// Kinematics q̇_NB = ½ q_NB ⊗ (0, w_NB_B) [1/s]: a body-frame rate perturbs the
/// attitude on the right, q(t+dt) = q ⊗ exp(w dt/2) (Solà, "Quaternion kinematics
/// for the error-state Kalman filter", arXiv:1711.02508, §4 — Hamilton convention).
Eigen::Quaterniond quatDerivative(const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& w_NB_B);

/// [rad] Angle between two non-zero vectors, in [0, π].
double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace flatsat::sim
