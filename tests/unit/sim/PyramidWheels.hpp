// SPDX-License-Identifier: Apache-2.0
#pragma once
// What the DynamicsModel tests share: their step and one wheel set for
// their small satellites.
#include <cmath>

#include "sim/RigidBodyWheels.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim::test {

/// [ns] the rig's step, at which the DynamicsModel tests step.
inline constexpr SimTime kStep = 100'000'000;

/// Four 2e-3 kg m² wheels (0.01 N m, 0.3 N m s) in a pyramid about body z:
/// axes (±√(2/3), 0, √(1/3)) and (0, ±√(2/3), √(1/3)).
inline void fitPyramidWheels(RigidBodyParams& body) {
  body.wheel_count = 4;
  const double s = std::sqrt(2.0 / 3.0);
  const double c = std::sqrt(1.0 / 3.0);
  body.wheel_axes_B << s, 0.0, -s, 0.0,  //
      0.0, s, 0.0, -s,                   //
      c, c, c, c;
  body.wheel_inertia_kg_m2.setConstant(2e-3);
  body.wheel_max_torque_Nm.setConstant(0.01);
  body.wheel_max_momentum_Nms.setConstant(0.3);
}

}  // namespace flatsat::sim::test
