// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bus/NodeMain.hpp"
#include "bus/Scenario.hpp"
#include "sim/ActuatorFaults.hpp"
#include "sim/DynamicsParams.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::dynamics_server {

/// Everything the dynamics server reads from a scenario.
struct DynamicsServerParams {
  sim::DynamicsParams dynamics;
  std::vector<sim::ActuatorFault> faults;     ///< the vehicle's `spacecraft.faults`, timed in simulated time
  std::int64_t step_period_ns = 100'000'000;  ///< [ns] base period
  std::uint64_t final_step = 0;               ///< [-] last step index of the run
  double orbit_period_s = 0.0;                ///< [s] for reporting
  /// A reaction wheel unit on the bench (paced runs): the bridge whose flatsat/wheel_tach
  /// samples are its rotors' speeds, which the plant's rotors then follow; "" : the
  /// commanded torques drive the plant's rotors.
  std::string wheels_follow;
};

/// The truth plant's vehicle part: everything of `truth` the physics uses.
/// The rest (gravity gradient, disturbance torque, initial state, substeps)
/// keeps the DynamicsParams defaults.
sim::DynamicsParams truthPlant(const vehicle::VehicleDescription& truth);

/// The plant from `vehicle.truth`, then `environment.gravity_gradient` and
/// `.disturbance_torque_body_Nm`, `initial` and components.<name>; every
/// problem goes to `problems` with file, key and reason.
DynamicsServerParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                const bus::NodeArgs& args, bus::ConfigProblems& problems);

}  // namespace flatsat::dynamics_server
