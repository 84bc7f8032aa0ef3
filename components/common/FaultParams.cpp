// SPDX-License-Identifier: Apache-2.0
#include "components/common/FaultParams.hpp"

#include "bus/FaultFields.hpp"

namespace flatsat {

namespace {

const std::string kSensorFaultKinds = "stuck, bias, noise, spike, dropout, saturation";

}  // namespace

std::vector<SensorFault> readSensorFaults(bus::ParamReader& reader, int channels,
                                          std::string_view unit) {
  return bus::readFaults<SensorFault>(
      reader, unit, kSensorFaultKinds, SensorFaults<3>::kMaxFaults, parseSensorFaultKind,
      [channels](const SensorFault& f) { return f.validate(channels); });
}

std::vector<std::string> toSensorFault(const msg::FaultCmd& command, int channels,
                                       SensorFault& fault) {
  return bus::faultFromCommand(command, fault, kSensorFaultKinds, parseSensorFaultKind,
                               [channels](const SensorFault& f) { return f.validate(channels); });
}

}  // namespace flatsat
