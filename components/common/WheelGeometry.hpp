// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/RigidBodyWheels.hpp"

namespace flatsat {

/// Reaction-wheel geometry as the controllers see it: up to kMaxWheels slots, of which the
/// first `count` are live. Filled from the vehicle's onboard view by the nodes (wheelGeometryOf).
struct WheelGeometry {
  static constexpr int kMaxWheels = 4;

  int count = 3;  // [-] live wheels (slots 0..count-1), 1..kMaxWheels
  // [-] unit spin axes in body axes, columns 0..count-1 (default x, y, z; slot 3 unused)
  Eigen::Matrix<double, 3, kMaxWheels> axes_B = Eigen::Matrix<double, 3, kMaxWheels>::Identity();
  // [kg·m²] rotor inertia about its spin axis, > 0 for the live wheels
  Eigen::Vector4d inertia_kg_m2 = Eigen::Vector4d::Constant(1.0e-4);

  /// Every violation as "<prefix>.field: reason" (e.g. "wheels.count: must be in 1..4");
  /// empty when valid. Slots past count are not checked.
  std::vector<std::string> validate(const std::string& prefix) const;

  /// [Nms] stored wheel momentum h_w_B = Σ a_i I_i Ω_i over the live wheels, body axes.
  /// Unused slots of wheel_speed_rad_s [rad/s] (relative to the body) are never read.
  Eigen::Vector3d momentum_B_Nms(const Eigen::Vector4d& wheel_speed_rad_s) const;

  /// [-] axes_B with the columns of unused slots set to zero.
  Eigen::Matrix<double, 3, kMaxWheels> liveAxes_B() const;
};

/// The wheels of a vehicle's body (vehicle/VehicleDescription.hpp) as the controllers see them.
inline WheelGeometry wheelGeometryOf(const sim::RigidBodyParams& body) {
  return {body.wheel_count, body.wheel_axes_B, body.wheel_inertia_kg_m2};
}

}  // namespace flatsat
