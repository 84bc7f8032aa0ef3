// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>

#include "bus/Scenario.hpp"
#include "sim/ActuatorFaults.hpp"
#include "sim/DynamicsModel.hpp"
#include "msg/Faults.h"

namespace flatsat::sim {

/// Everything the dynamics server reads from a scenario.
struct DynamicsServerParams {
  DynamicsParams dynamics;
  std::vector<ActuatorFault> faults;          ///< `faults:` of the server's section, timed in simulated time
  std::int64_t step_period_ns = 100'000'000;  ///< [ns] base period
  std::uint64_t final_step = 0;               ///< [-] last step index of the run
  double orbit_period_s = 0.0;                ///< [s] for reporting
};

/// Reads the plant sections (spacecraft, orbit, environment, initial) and
/// components.<name>; every problem goes to `problems` with file, key and
/// reason. The IGRF file is looked up next to the scenario, then in the
/// project's data folder.
DynamicsServerParams readDynamicsServerParams(const bus::Scenario& scenario,
                                              const std::string& name,
                                              bus::ConfigProblems& problems);

/// `faults:` of the server's section: a list of {kind, channel, magnitude,
/// start_s, duration_s} for the plant's actuators (sim/ActuatorFaults.hpp).
std::vector<ActuatorFault> readActuatorFaults(bus::ParamReader& reader, const DynamicsParams& plant);

/// A fault command to the dynamics server as an actuator fault, for a plant
/// with that many wheels and thrusters; every problem (empty: valid).
std::vector<std::string> toActuatorFault(const msg::FaultCmd& command, int wheels, int thrusters,
                                         ActuatorFault& fault);

/// The plant sections alone (spacecraft, orbit, environment, initial), for
/// components that carry onboard knowledge of them (wheel geometry, orbit,
/// field model); the dynamics server reports their problems, so callers
/// may pass a scratch list.
DynamicsParams readPlant(const bus::Scenario& scenario, bus::ConfigProblems& problems);

}  // namespace flatsat::sim
