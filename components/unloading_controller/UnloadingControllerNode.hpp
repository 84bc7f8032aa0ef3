// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <mutex>
#include <optional>

#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/LastValid.hpp"
#include "components/unloading_controller/MagneticModes.hpp"

namespace flatsat::unloading_controller {

/// The magnetorquers' owner: wheel speeds and measured field in, torquer
/// dipole out, in the mode the scenario or flatsat/unloading_mode_cmd sets
/// (unload, detumble, spin capture; MagneticModes).
class UnloadingControllerNode final : public bus::Component {
 public:
  UnloadingControllerNode(bus::Bus& bus, bus::NodeOptions options, const MagneticModesParams& params);

 private:
  void step(const bus::StepContext& ctx) override;
  void receive(const msg::ModeCmd& command);

  bus::InputOf<bus::topics::kWheelTach>& tach_ = addInput(bus::topics::kWheelTach);
  LastValid<msg::WheelTachReading> last_tach_;  // rides through tachometer dropouts
  bus::InputOf<bus::topics::kMagnetometer>& field_ = addInput(bus::topics::kMagnetometer);
  bus::WriterOf<bus::topics::kDipoleCmd>& command_ = addOutput(bus::topics::kDipoleCmd);
  std::mutex mode_mutex_;
  std::optional<MagneticMode> requested_mode_;  // received, entered at the next step
  bus::ReaderOf<bus::topics::kUnloadingModeCmd> mode_commands_;
  MagneticModes modes_;
};

/// components.<name>: the unloading keys (gain_per_s, h_*), `mode:`, a
/// `detumble:` and a `spin_capture:` section and the handover; the wheel
/// geometry from spacecraft.wheels, the coil limits from spacecraft.torquers
/// and the orbital rate from the orbit.
MagneticModesParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                               bus::ConfigProblems& problems);

}  // namespace flatsat::unloading_controller
