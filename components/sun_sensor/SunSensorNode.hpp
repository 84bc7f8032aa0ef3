// SPDX-License-Identifier: Apache-2.0
#pragma once
#include "bus/Convert.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/EmulatorNode.hpp"
#include "components/sun_sensor/SunSensorModel.hpp"

namespace flatsat::sun_sensor {

inline SunSensorInput toInput(const msg::TruthState& truth) {
  return {bus::vec3(truth.sun_body_unit()), truth.illumination()};
}

inline msg::SunSensorReading toMessage(const SunSensorOutput& out) {
  msg::SunSensorReading m;
  bus::put(m.sun_body_unit(), out.sun_B_unit);
  m.valid(out.valid);
  return m;
}

using SunSensorNode =
    EmulatorNode<SunSensorModel, bus::topics::kSunSensor, toInput, toMessage, &SunSensorOutput::sun_B_unit>;

/// components.<name> of the scenario.
EmulatorParams<SunSensorParams> readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                           bus::ConfigProblems& problems);

}  // namespace flatsat::sun_sensor
