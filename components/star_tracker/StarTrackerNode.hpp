// SPDX-License-Identifier: Apache-2.0
#pragma once
#include "bus/Convert.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/EmulatorNode.hpp"
#include "components/star_tracker/StarTrackerModel.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::star_tracker {

inline StarTrackerInput toInput(const msg::TruthState& truth) {
  return {bus::quat(truth.q_inertial_body()), bus::vec3(truth.w_body_rad_s()), bus::vec3(truth.sun_body_unit()),
          truth.illumination(), bus::vec3(truth.r_inertial_m())};
}

inline msg::StarTrackerReading toMessage(const StarTrackerOutput& out) {
  msg::StarTrackerReading m;
  bus::put(m.q_inertial_body(), applyError(out.q_NB_true, out.error_B_rad));
  m.valid(out.valid);
  return m;
}

/// Faults act on the measurement error: `bias` is a misalignment [rad] about a body axis.
using StarTrackerNode = EmulatorNode<StarTrackerModel, bus::topics::kStarTracker, toInput, toMessage,
                                     &StarTrackerOutput::error_B_rad>;

/// components.<name> of the scenario; the mounting is the vehicle's, as it is (truth)
/// and as the unit's configuration turns its attitude into body axes (onboard).
EmulatorParams<StarTrackerParams> readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                             const bus::NodeArgs& args, bus::ConfigProblems& problems);

}  // namespace flatsat::star_tracker

namespace flatsat {
// Compiled once, in StarTrackerNode.cpp; the process, the composed rig and the tests link it.
extern template class EmulatorNode<star_tracker::StarTrackerModel, bus::topics::kStarTracker,
                                   star_tracker::toInput, star_tracker::toMessage,
                                   &star_tracker::StarTrackerOutput::error_B_rad>;
}  // namespace flatsat
