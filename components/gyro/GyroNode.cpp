// SPDX-License-Identifier: Apache-2.0
#include "components/gyro/GyroNode.hpp"

#include "components/Processes.hpp"

namespace flatsat::gyro {

EmulatorParams<GyroParams> readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                         bus::ConfigProblems& problems) {
  return readEmulatorParams<GyroParams>(
      scenario, args.name, 3, "rad/s", problems, [&](bus::ParamReader& r, GyroParams& m) {
    r.read("angle_random_walk_rad_per_sqrt_s", m.angle_random_walk_rad_per_sqrt_s, "-");
    r.read("rate_random_walk_rad_per_s_sqrt_s", m.rate_random_walk_rad_per_s_sqrt_s, "-");
    r.read("bias0_body_rad_s", m.bias0_B_rad_s, "rad/s");
    r.read("scale_factor", m.scale_factor, "-");
    r.read("misalignment_rad", m.misalignment_rad, "rad");
      });
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<GyroNode>(argc, argv, "gyro", readParams);
}

}  // namespace flatsat::gyro

namespace flatsat {
template class EmulatorNode<gyro::GyroModel, bus::topics::kGyro, gyro::toInput, gyro::toMessage,
                            &gyro::GyroOutput::w_NB_B_rad_s>;
}  // namespace flatsat
