// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bus/NodeMain.hpp"
#include "components/thruster_sequencer/AngleOnlyLimitCycle.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat {

/// A kind of component the launcher can start.
struct ComponentKind {
  std::string name;        ///< as listed under components: in a scenario
  std::string executable;  ///< flatsat-<name>, next to the flatsat tool
  /// Reads the component's parameters, reporting every problem.
  std::function<void(const bus::Scenario&, const vehicle::Vehicle&, const bus::NodeArgs&, bus::ConfigProblems&)>
      check;
  /// Builds the node on a bus of this process (a composed rig) with `options`;
  /// empty when the kind cannot be composed (see not_composable).
  std::function<std::unique_ptr<bus::Node>(bus::Bus&, bus::NodeOptions, const bus::Scenario&,
                                           const vehicle::Vehicle&, const bus::NodeArgs&)>
      make;
  std::string not_composable;  ///< why a composed rig cannot hold it (empty: it can)
  /// The registry topics a kind that cannot be composed reads (its DDS Security
  /// grant, tools/GrantsCommand.hpp); a composable kind's are seen on an in-process bus.
  std::vector<std::string> reads;
};

const std::vector<ComponentKind>& componentKinds();
const ComponentKind* findComponentKind(const std::string& name);

/// Every problem of a scenario: the vehicle (read once), each listed
/// component's parameters, unknown component names, a missing time master or
/// recorder, and what components need of each other. Empty when the rig can start.
std::vector<std::string> checkScenario(const bus::Scenario& scenario, const std::string& out_dir);

/// What a valid scenario may not do as its author meant, one line each with
/// file and key (the seed S1 example's T2, which breaks the seed's own
/// condition, is one): the run logs them as warnings and goes on.
std::vector<std::string> scenarioCautions(const bus::Scenario& scenario);

/// Seed S1's condition on T2 for this rig: the angle-only sequencer braking
/// the initial drift about its axis (`initial.w_body_rad_s`), with the pulse
/// its onboard thrusters and inertia give and the Sun sensor's sample period.
/// Empty without a valid angle-only thruster_sequencer.
std::optional<thruster_sequencer::BrakingReach> angleOnlyBrakingReach(const bus::Scenario& scenario,
                                                                      const vehicle::Vehicle& vehicle);

}  // namespace flatsat
