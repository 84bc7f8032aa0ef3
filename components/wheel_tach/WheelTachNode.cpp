// SPDX-License-Identifier: Apache-2.0
#include "components/wheel_tach/WheelTachNode.hpp"

#include "components/Processes.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::wheel_tach {

EmulatorParams<WheelTachParams> readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                           const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  const int wheels = vehicle.truth.body.wheel_count;  // an emulator measures what is there
  return readEmulatorParams<WheelTachParams>(
      scenario, args.name, 4, "rad/s", problems, [&](bus::ParamReader& r, WheelTachParams& m) {
    m.wheel_count = wheels;
    r.read("noise_rad_s", m.noise_rad_s, "rad/s");
    r.read("quantum_rad_s", m.quantum_rad_s, "rad/s");
      });
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<WheelTachNode>(argc, argv, "wheel_tach", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::wheel_tach

namespace flatsat {
template class EmulatorNode<wheel_tach::WheelTachModel, bus::topics::kWheelTach, wheel_tach::toInput,
                            wheel_tach::toMessage, &wheel_tach::WheelTachOutput::wheel_speed_rad_s>;
}  // namespace flatsat
