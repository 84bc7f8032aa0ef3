// SPDX-License-Identifier: Apache-2.0
#pragma once
#include "bus/Convert.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/EmulatorNode.hpp"
#include "components/sun_sensor/SunSensorModel.hpp"
#include "sim/PanelModel.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::sun_sensor {

inline SunSensorInput toInput(const msg::TruthState& truth) {
  return {bus::vec3(truth.sun_body_unit()), truth.illumination(), truth.solar_flux_W_m2() / sim::kSolarFlux1Au_W_m2,
          bus::quat(truth.q_inertial_body()).conjugate() * bus::vec3(truth.r_inertial_m())};
}

inline msg::SunSensorReading toMessage(const SunSensorOutput& out) {
  msg::SunSensorReading m;
  bus::put(m.sun_body_unit(), out.sun_B_unit);
  m.valid(out.valid);
  m.cell_count(static_cast<std::uint32_t>(out.cell_count));
  for (int i = 0; i < out.cell_count; ++i) m.cell_output()[static_cast<std::size_t>(i)] = out.cell_output[static_cast<std::size_t>(i)];
  return m;
}

using SunSensorNode =
    EmulatorNode<SunSensorModel, bus::topics::kSunSensor, toInput, toMessage, &SunSensorOutput::sun_B_unit>;

/// components.<name> of the scenario; the boresight is the vehicle's mounting, as it
/// is (truth) and as flight software converts with it (onboard).
EmulatorParams<SunSensorParams> readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                           const bus::NodeArgs& args, bus::ConfigProblems& problems);

}  // namespace flatsat::sun_sensor

namespace flatsat {
// Compiled once, in SunSensorNode.cpp; the process, the composed rig and the tests link it.
extern template class EmulatorNode<sun_sensor::SunSensorModel, bus::topics::kSunSensor, sun_sensor::toInput,
                                   sun_sensor::toMessage, &sun_sensor::SunSensorOutput::sun_B_unit>;
}  // namespace flatsat
