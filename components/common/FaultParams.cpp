// SPDX-License-Identifier: Apache-2.0
#include "components/common/FaultParams.hpp"

#include <cmath>

#include "bus/Stamp.hpp"

namespace flatsat {

std::vector<SensorFault> readSensorFaults(bus::ParamReader& reader, int channels,
                                          std::string_view unit) {
  std::vector<SensorFault> faults;
  for (auto& entry : reader.list("faults")) {
    SensorFault fault;
    std::string kind;
    entry.read("kind", kind);
    if (!parseSensorFaultKind(kind, fault.kind)) {
      entry.problem("kind", "'" + kind +
                                "' is not a sensor fault (stuck, bias, noise, spike, dropout, saturation)");
    }
    entry.read("channel", fault.channel);
    entry.read("magnitude", fault.magnitude, unit);
    double start_s = 0.0, duration_s = 0.0;
    entry.read("start_s", start_s, "s");
    entry.read("duration_s", duration_s, "s");
    fault.start_ns = std::llround(start_s * 1e9);
    fault.duration_ns = std::llround(duration_s * 1e9);
    entry.problems(fault.validate(channels));
    entry.finish();
    faults.push_back(fault);
  }
  if (faults.size() > static_cast<std::size_t>(SensorFaults<3>::kMaxFaults)) {
    reader.problem("faults", "at most " + std::to_string(SensorFaults<3>::kMaxFaults) + " faults");
  }
  return faults;
}

std::vector<std::string> toSensorFault(const msg::FaultCmd& command, int channels,
                                       SensorFault& fault) {
  std::vector<std::string> problems;
  const std::string kind = bus::text(command.kind());
  if (!parseSensorFaultKind(kind, fault.kind)) {
    problems.push_back("kind: '" + kind + "' is not a sensor fault");
  }
  fault.channel = command.channel();
  fault.magnitude = command.magnitude();
  fault.start_ns = command.start_ns();
  fault.duration_ns = command.duration_ns();
  for (auto& p : fault.validate(channels)) problems.push_back(std::move(p));
  return problems;
}

}  // namespace flatsat
