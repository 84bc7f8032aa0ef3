// SPDX-License-Identifier: Apache-2.0
#pragma once
#include "bus/Convert.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/EmulatorNode.hpp"
#include "components/magnetometer/MagnetometerModel.hpp"

namespace flatsat::magnetometer {

inline MagnetometerInput toInput(const msg::TruthState& truth) {
  return {bus::vec3(truth.b_body_T()), bus::vec3(truth.dipole_at_sample_body_Am2())};
}

inline msg::MagnetometerReading toMessage(const MagnetometerOutput& out) {
  msg::MagnetometerReading m;
  bus::put(m.b_body_T(), out.b_B_T);
  m.saturated(out.saturated);
  m.valid(!out.blanked);  // the fault layer may clear it too
  return m;
}

using MagnetometerNode =
    EmulatorNode<MagnetometerModel, bus::topics::kMagnetometer, toInput, toMessage, &MagnetometerOutput::b_B_T>;

/// components.<name> of the scenario.
EmulatorParams<MagnetometerParams> readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                              bus::ConfigProblems& problems);

}  // namespace flatsat::magnetometer

namespace flatsat {
// Compiled once, in MagnetometerNode.cpp; the process, the composed rig and the tests link it.
extern template class EmulatorNode<magnetometer::MagnetometerModel, bus::topics::kMagnetometer,
                                   magnetometer::toInput, magnetometer::toMessage,
                                   &magnetometer::MagnetometerOutput::b_B_T>;
}  // namespace flatsat
