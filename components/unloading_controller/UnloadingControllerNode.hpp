// SPDX-License-Identifier: Apache-2.0
#pragma once
#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/LastValid.hpp"
#include "components/unloading_controller/CrossProductUnloading.hpp"

namespace flatsat::unloading_controller {

/// Magnetic momentum unloading: wheel speeds and measured field in, torquer
/// dipole out.
class UnloadingControllerNode final : public bus::Component {
 public:
  UnloadingControllerNode(bus::Bus& bus, bus::NodeOptions options,
                          const CrossProductUnloadingParams& params);

 private:
  void step(const bus::StepContext& ctx) override;

  bus::InputOf<bus::topics::kWheelTach>& tach_ = addInput(bus::topics::kWheelTach);
  LastValid<msg::WheelTachReading> last_tach_;  // rides through tachometer dropouts
  bus::InputOf<bus::topics::kMagnetometer>& field_ = addInput(bus::topics::kMagnetometer);
  bus::WriterOf<bus::topics::kDipoleCmd>& command_ = addOutput(bus::topics::kDipoleCmd);
  CrossProductUnloading law_;
};

/// components.<name>, with the wheel geometry from spacecraft.wheels and
/// the coil limits from spacecraft.torquers.
CrossProductUnloadingParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                                       bus::ConfigProblems& problems);

}  // namespace flatsat::unloading_controller
