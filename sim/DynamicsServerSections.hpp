// SPDX-License-Identifier: Apache-2.0
#pragma once
// Section readers of readPlant() that live in their own source files.
#include "bus/Params.hpp"
#include "sim/DynamicsParams.hpp"

namespace flatsat::sim {

/// spacecraft: inertia, wheels, torquers, mass and cannonball areas (after the
/// orbit section: which of them are required depends on orbit.propagator),
/// panels, thrusters, flaps.
void readSpacecraft(bus::ParamReader spacecraft, DynamicsParams& p);

}  // namespace flatsat::sim
