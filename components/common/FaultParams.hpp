// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <string_view>
#include <vector>

#include "bus/Params.hpp"
#include "components/common/SensorFaults.hpp"
#include "msg/Faults.h"

namespace flatsat {

/// Reads `faults:` of a sensor's scenario section: a list of
/// {kind, channel, magnitude, start_s, duration_s}; magnitude is in the
/// measurement's unit (`unit`, e.g. "T", "rad/s").
std::vector<SensorFault> readSensorFaults(bus::ParamReader& reader, int channels,
                                          std::string_view unit);

/// A fault command as a sensor fault; returns every problem (empty: valid).
std::vector<std::string> toSensorFault(const msg::FaultCmd& command, int channels,
                                       SensorFault& fault);

}  // namespace flatsat
