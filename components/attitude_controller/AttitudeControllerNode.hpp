// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>

#include "bus/CommandAcks.hpp"
#include "bus/ParamCommands.hpp"
#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/LastValid.hpp"
#include "components/attitude_controller/SunPointingController.hpp"
#include "components/common/onboard/ReferenceModel.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::attitude_controller {

struct AttitudeControllerNodeParams {
  SunPointingControllerParams law;
  /// `target: s2_orbital`: hold seed S2's orbital frame (sim::R_N_S2Orbital) from this
  /// onboard orbit; nullopt (`target: sun`, the default): point pointing_axis_body at the Sun.
  std::optional<onboard::ReferenceModelParams> s2_orbital;
};

/// Wheel-based pointing: attitude estimate and wheel speeds in, wheel motor
/// torques out; the target is the Sun or seed S2's orbital frame. Its gains and
/// limits can be changed while it runs (flatsat/param_cmd, `flatsat cmd param`),
/// each change acknowledged.
class AttitudeControllerNode final : public bus::Component {
 public:
  AttitudeControllerNode(bus::Bus& bus, bus::NodeOptions options, const AttitudeControllerNodeParams& params);

 private:
  void step(const bus::StepContext& ctx) override;

  bus::InputOf<bus::topics::kAttitudeEstimate>& estimate_ =
      addInput(bus::topics::kAttitudeEstimate);
  bus::InputOf<bus::topics::kWheelTach>& tach_ = addInput(bus::topics::kWheelTach);
  LastValid<msg::WheelTachReading> last_tach_;  // rides through tachometer dropouts
  bus::WriterOf<bus::topics::kWheelTorqueCmd>& command_ =
      addOutput(bus::topics::kWheelTorqueCmd);
  SunPointingController controller_;
  std::optional<onboard::ReferenceModel> onboard_;  // local orbital target only
  bus::CommandAcks acks_{bus_};
  bus::ParamCommands<SunPointingControllerParams> params_;
};

/// components.<name>, with the wheel geometry and orbit knowledge of the vehicle's onboard view.
AttitudeControllerNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                        const bus::NodeArgs& args, bus::ConfigProblems& problems);

}  // namespace flatsat::attitude_controller
