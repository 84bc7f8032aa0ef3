// SPDX-License-Identifier: Apache-2.0
#include "components/gyro/GyroNode.hpp"

namespace flatsat::gyro {

GyroParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                      bus::ConfigProblems& problems) {
  GyroParams p;
  p.seed = scenario.seedFor(args.name);
  auto r = scenario.componentParams(args.name, problems);
  r.read("angle_random_walk_rad_per_sqrt_s", p.angle_random_walk_rad_per_sqrt_s, "-");
  r.read("rate_random_walk_rad_per_s_sqrt_s", p.rate_random_walk_rad_per_s_sqrt_s, "-");
  r.read("bias0_body_rad_s", p.bias0_B_rad_s, "rad/s");
  r.read("seed", p.seed);
  r.problems(p.validate());
  r.finish();
  return p;
}

}  // namespace flatsat::gyro
