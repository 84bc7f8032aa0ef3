// SPDX-License-Identifier: Apache-2.0
#include "components/magnetometer/MagnetometerNode.hpp"

namespace flatsat::magnetometer {

MagnetometerParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                              bus::ConfigProblems& problems) {
  MagnetometerParams p;
  p.seed = scenario.seedFor(args.name);
  auto r = scenario.componentParams(args.name, problems);
  r.read("noise_T", p.noise_T, "T");
  r.read("bias_body_T", p.bias_B_T, "T");
  r.read("scale_factor", p.scale_factor, "-");
  r.read("quantum_T", p.quantum_T, "T");
  r.read("range_T", p.range_T, "T");
  r.read("seed", p.seed);
  r.problems(p.validate());
  r.finish();
  return p;
}

}  // namespace flatsat::magnetometer
