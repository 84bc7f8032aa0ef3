// SPDX-License-Identifier: Apache-2.0
#include "components/sun_sensor/SunSensorNode.hpp"

namespace flatsat::sun_sensor {

SunSensorParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                           bus::ConfigProblems& problems) {
  SunSensorParams p;
  p.seed = scenario.seedFor(args.name);
  auto r = scenario.componentParams(args.name, problems);
  r.read("boresight_body", p.boresight_B, "-");
  r.read("noise_rad", p.noise_rad, "rad");
  r.read("fov_half_angle_rad", p.fov_half_angle_rad, "rad");
  r.read("min_illumination", p.min_illumination, "-");
  r.read("seed", p.seed);
  r.problems(p.validate());
  r.finish();
  return p;
}

}  // namespace flatsat::sun_sensor
