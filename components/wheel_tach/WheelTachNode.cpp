// SPDX-License-Identifier: Apache-2.0
#include "components/wheel_tach/WheelTachNode.hpp"

#include "sim/DynamicsServerParams.hpp"

namespace flatsat::wheel_tach {

WheelTachParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                           bus::ConfigProblems& problems) {
  bus::ConfigProblems reported_by_dynamics_server;
  WheelTachParams p;
  p.wheel_count = sim::readPlant(scenario, reported_by_dynamics_server).body.wheel_count;
  p.seed = scenario.seedFor(args.name);
  auto r = scenario.componentParams(args.name, problems);
  r.read("noise_rad_s", p.noise_rad_s, "rad/s");
  r.read("quantum_rad_s", p.quantum_rad_s, "rad/s");
  r.read("seed", p.seed);
  r.problems(p.validate());
  r.finish();
  return p;
}

}  // namespace flatsat::wheel_tach
