// SPDX-License-Identifier: Apache-2.0
#pragma once
#include "bus/Convert.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/EmulatorNode.hpp"
#include "components/gyro/GyroModel.hpp"

namespace flatsat::gyro {

inline GyroInput toInput(const msg::TruthState& truth) { return {bus::vec3(truth.w_body_rad_s())}; }

inline msg::GyroReading toMessage(const GyroOutput& out) {
  msg::GyroReading m;
  bus::put(m.w_body_rad_s(), out.w_NB_B_rad_s);
  m.valid(true);  // the fault layer may clear it
  return m;
}

using GyroNode =
    EmulatorNode<GyroModel, bus::topics::kGyro, toInput, toMessage, &GyroOutput::w_NB_B_rad_s>;

/// components.<name> of the scenario.
EmulatorParams<GyroParams> readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                                      bus::ConfigProblems& problems);

}  // namespace flatsat::gyro

namespace flatsat {
// Compiled once, in GyroNode.cpp; the process, the composed rig and the tests link it.
extern template class EmulatorNode<gyro::GyroModel, bus::topics::kGyro, gyro::toInput, gyro::toMessage,
                                   &gyro::GyroOutput::w_NB_B_rad_s>;
}  // namespace flatsat
