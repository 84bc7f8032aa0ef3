// SPDX-License-Identifier: Apache-2.0
#include "components/magnetometer/MagnetometerNode.hpp"

#include "components/Processes.hpp"

namespace flatsat::magnetometer {

EmulatorParams<MagnetometerParams> readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                                 bus::ConfigProblems& problems) {
  return readEmulatorParams<MagnetometerParams>(
      scenario, args.name, 3, "T", problems, [&](bus::ParamReader& r, MagnetometerParams& m) {
    r.read("noise_T", m.noise_T, "T");
    r.read("bias_body_T", m.bias_B_T, "T");
    r.read("scale_factor", m.scale_factor, "-");
    r.read("quantum_T", m.quantum_T, "T");
    r.read("range_T", m.range_T, "T");
    r.read("misalignment_rad", m.misalignment_rad, "rad");
    r.read("coil_coupling_T_per_Am2", m.coil_coupling_T_per_Am2, "T/(A m^2)");
    r.read("blank_while_coils_on", m.blank_while_coils_on);
      });
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<MagnetometerNode>(argc, argv, "magnetometer", readParams);
}

}  // namespace flatsat::magnetometer

namespace flatsat {
template class EmulatorNode<magnetometer::MagnetometerModel, bus::topics::kMagnetometer,
                            magnetometer::toInput, magnetometer::toMessage,
                            &magnetometer::MagnetometerOutput::b_B_T>;
}  // namespace flatsat
