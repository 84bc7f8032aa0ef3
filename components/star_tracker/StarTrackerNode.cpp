// SPDX-License-Identifier: Apache-2.0
#include "components/star_tracker/StarTrackerNode.hpp"

#include "components/Processes.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::star_tracker {

EmulatorParams<StarTrackerParams> readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                             const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  return readEmulatorParams<StarTrackerParams>(
      scenario, args.name, 3, "rad", problems, [&](bus::ParamReader& r, StarTrackerParams& m) {
        m.q_body_sensor = vehicle.truth.sensors.q_body_star_tracker;
        m.q_body_sensor_onboard = vehicle.onboard.sensors.q_body_star_tracker;
        vehicle::refuseMovedKeys(r, {{"q_body_sensor", "spacecraft.sensors.star_tracker.q_body_sensor"}});
        r.read("noise_cross_rad", m.noise_cross_rad, "rad");
        r.read("noise_about_rad", m.noise_about_rad, "rad");
        r.read("max_rate_rad_s", m.max_rate_rad_s, "rad/s");
        r.read("sun_exclusion_rad", m.sun_exclusion_rad, "rad");
        r.read("earth_exclusion_rad", m.earth_exclusion_rad, "rad");
      });
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<StarTrackerNode>(argc, argv, "star_tracker", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::star_tracker

namespace flatsat {
template class EmulatorNode<star_tracker::StarTrackerModel, bus::topics::kStarTracker, star_tracker::toInput,
                            star_tracker::toMessage, &star_tracker::StarTrackerOutput::error_B_rad>;
}  // namespace flatsat
