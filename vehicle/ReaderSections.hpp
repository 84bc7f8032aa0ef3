// SPDX-License-Identifier: Apache-2.0
#pragma once
// Section readers of readVehicle() that live in their own source files.
#include "bus/Params.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::vehicle {

/// The actuator fault kinds (sim/ActuatorFaults.hpp), as problems list them.
inline const std::string kActuatorFaultKinds = "wheel_failed, wheel_stuck, wheel_degraded, coil_open, thruster_failed";

/// spacecraft: inertia, wheels, torquers, mass and cannonball areas (after the
/// orbit section: which of them are required depends on orbit.propagator),
/// panels, thrusters, flaps, sensor mountings and timed actuator faults.
void readSpacecraft(bus::ParamReader spacecraft, VehicleDescription& v);

/// sensors: {sun_sensor: {boresight_body}, star_tracker: {q_body_sensor},
/// magnetometer: {q_body_sensor}}, of spacecraft or of onboard.
void readSensorMountings(bus::ParamReader sensors, SensorMountings& mountings);

/// `faults:` of the reader's mapping: timed actuator faults {kind, channel,
/// magnitude, start_s, duration_s} of this vehicle's wheels, coils and thrusters.
std::vector<sim::ActuatorFault> readActuatorFaults(bus::ParamReader& reader, const VehicleDescription& v);

}  // namespace flatsat::vehicle
