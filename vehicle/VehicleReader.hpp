// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "bus/NodeMain.hpp"
#include "bus/Params.hpp"
#include "bus/Scenario.hpp"
#include "msg/Faults.h"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::vehicle {

/// The vehicle of a scenario: `orbit`, `spacecraft`, the field and density
/// keys of `environment` (kEnvironmentKeys), and the `onboard` view laid over
/// the truth item by item. Every problem goes to `problems` with file, key
/// and reason. The IGRF and WMM files are looked up next to the scenario,
/// then in the project's data folder.
Vehicle readVehicle(const bus::Scenario& scenario, bus::ConfigProblems& problems);

/// readVehicle() of a scenario already checked (checkScenario).
/// @throws bus::ScenarioError listing every problem.
Vehicle vehicleOf(const bus::Scenario& scenario);

/// The keys of `environment` readVehicle() reads; the dynamics server reads the rest.
extern const std::vector<std::string> kEnvironmentKeys;

/// Keys a component's section held before the vehicle took them over, each
/// {old key, where it is given now}: one that is still given is refused with
/// the new place, and finish() does not call it unknown.
void refuseMovedKeys(bus::ParamReader& section, const std::vector<std::pair<std::string, std::string>>& moved);

/// The onboard models' keys of the estimator and the controllers, now the onboard view's.
inline const std::vector<std::pair<std::string, std::string>> kMovedReferenceKeys = {
    {"reference_field", "onboard.field_model"}, {"reference_orbit", "onboard.orbit.propagator"}};

/// A fault command to the dynamics server as an actuator fault, for a plant
/// with that many wheels and thrusters; every problem (empty: valid).
std::vector<std::string> toActuatorFault(const msg::FaultCmd& command, int wheels, int thrusters,
                                         sim::ActuatorFault& fault);

/// A component reader `read(scenario, vehicle, args, problems)` as the
/// `read(scenario, args, problems)` a process's main takes: the vehicle is
/// read first, its problems reported with the component's.
template <class Read>
auto withVehicle(Read read) {
  return [read](const bus::Scenario& scenario, const bus::NodeArgs& args, bus::ConfigProblems& problems) {
    const Vehicle vehicle = readVehicle(scenario, problems);
    return read(scenario, vehicle, args, problems);
  };
}

}  // namespace flatsat::vehicle
