// SPDX-License-Identifier: Apache-2.0
#pragma once
#include "bus/Convert.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/EmulatorNode.hpp"
#include "components/wheel_tach/WheelTachModel.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::wheel_tach {

inline WheelTachInput toInput(const msg::TruthState& truth) {
  return {bus::vec4(truth.wheel_speed_rad_s())};
}

inline msg::WheelTachReading toMessage(const WheelTachOutput& out) {
  msg::WheelTachReading m;
  bus::put(m.wheel_speed_rad_s(), out.wheel_speed_rad_s);
  m.valid(true);  // the fault layer may clear it
  return m;
}

using WheelTachNode =
    EmulatorNode<WheelTachModel, bus::topics::kWheelTach, toInput, toMessage, &WheelTachOutput::wheel_speed_rad_s>;

/// components.<name> of the scenario; the wheel count is the vehicle's (truth).
EmulatorParams<WheelTachParams> readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                           const bus::NodeArgs& args, bus::ConfigProblems& problems);

}  // namespace flatsat::wheel_tach

namespace flatsat {
// Compiled once, in WheelTachNode.cpp; the process, the composed rig and the tests link it.
extern template class EmulatorNode<wheel_tach::WheelTachModel, bus::topics::kWheelTach, wheel_tach::toInput,
                                   wheel_tach::toMessage, &wheel_tach::WheelTachOutput::wheel_speed_rad_s>;
}  // namespace flatsat
