// SPDX-License-Identifier: Apache-2.0
#pragma once
#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/LastValid.hpp"
#include "components/unloading_controller/CoilArbiter.hpp"
#include "components/unloading_controller/CrossProductUnloading.hpp"

namespace flatsat::unloading_controller {

/// Where the unloading law takes the field from.
enum class FieldSource {
  kMagnetometer,  ///< flatsat/magnetometer
  kS0Estimate,    ///< flatsat/field_estimate (seed S0, no magnetometer); serves coil requests
};

struct UnloadingControllerNodeParams {
  CrossProductUnloadingParams law;
  FieldSource field_source = FieldSource::kMagnetometer;
};

/// Magnetic momentum unloading and owner of the torquers: wheel speeds and the
/// field in, torquer dipole out; windows other components request (seed S0)
/// hold the coils through the CoilArbiter and are reported on flatsat/coil_window.
class UnloadingControllerNode final : public bus::Component {
 public:
  UnloadingControllerNode(bus::Bus& bus, bus::NodeOptions options,
                          const UnloadingControllerNodeParams& params);

 private:
  void step(const bus::StepContext& ctx) override;

  bus::InputOf<bus::topics::kWheelTach>& tach_ = addInput(bus::topics::kWheelTach);
  LastValid<msg::WheelTachReading> last_tach_;  // rides through tachometer dropouts
  bus::InputOf<bus::topics::kMagnetometer>* magnetometer_ = nullptr;   // kMagnetometer
  bus::InputOf<bus::topics::kFieldEstimate>* field_estimate_ = nullptr;  // kS0Estimate
  bus::InputOf<bus::topics::kCoilRequest>* coil_request_ = nullptr;      // kS0Estimate
  bus::WriterOf<bus::topics::kCoilWindow>& coil_window_ = addOutput(bus::topics::kCoilWindow);
  bus::WriterOf<bus::topics::kDipoleCmd>& command_ = addOutput(bus::topics::kDipoleCmd);
  CrossProductUnloading law_;
  CoilArbiter arbiter_;
};

/// components.<name>, with the wheel geometry from spacecraft.wheels and
/// the coil limits from spacecraft.torquers.
UnloadingControllerNodeParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                                         bus::ConfigProblems& problems);

}  // namespace flatsat::unloading_controller
