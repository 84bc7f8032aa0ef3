// SPDX-License-Identifier: Apache-2.0
#include "components/sun_sensor/SunSensorNode.hpp"

namespace flatsat::sun_sensor {

EmulatorParams<SunSensorParams> readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                              bus::ConfigProblems& problems) {
  return readEmulatorParams<SunSensorParams>(
      scenario, args.name, 3, "-", problems, [&](bus::ParamReader& r, SunSensorParams& m) {
    r.read("boresight_body", m.boresight_B, "-");
    r.read("noise_rad", m.noise_rad, "rad");
    r.read("fov_half_angle_rad", m.fov_half_angle_rad, "rad");
    r.read("min_illumination", m.min_illumination, "-");
      });
}

}  // namespace flatsat::sun_sensor
