// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <mutex>
#include <optional>
#include <vector>

#include "bus/CommandAcks.hpp"
#include "bus/ParamCommands.hpp"
#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/LastValid.hpp"
#include "components/unloading_controller/CoilArbiter.hpp"
#include "components/common/onboard/ReferenceModel.hpp"
#include "components/unloading_controller/MagneticModes.hpp"
#include "sim/Atmosphere.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::unloading_controller {

/// Where the magnetic laws take the field from.
enum class FieldSource {
  kMagnetometer,  ///< flatsat/magnetometer
  kFieldFromMomentum,    ///< flatsat/field_estimate (seed S0, no magnetometer); serves coil requests
  kModelAttitude, ///< onboard field model turned into body axes by flatsat/attitude_estimate
};

/// What the flight software knows of seed S2's flaps to turn torque into angles:
/// K = 2ρA_pV²l (sim/Flaps.hpp) from the onboard orbit and density model.
struct FlapKnowledge {
  double plate_area_m2 = 0.0;  // [m²] A_p, > 0
  double lever_arm_m = 0.0;    // [m] l, > 0
  std::optional<sim::AtmosphereParams> atmosphere;  // onboard density model; nullopt: the constant
  double density_kg_m3 = 0.0;  // [kg/m³] constant density without a model, >= 0
};

struct UnloadingControllerNodeParams {
  MagneticModesParams modes;
  FieldSource field_source = FieldSource::kMagnetometer;
  /// [-] coils off over this last fraction of every step the laws drive them, so the
  /// magnetometer samples the Earth's field alone (duty-cycling), in [0, 1).
  double quiet_fraction = 0.0;
  /// Onboard orbit and field model; set for kModelAttitude and when spin capture
  /// takes the field's turn from it.
  std::optional<onboard::ReferenceModelParams> onboard;
  /// Set with modes.aero (the `aero:` section), which needs it and onboard for K.
  std::optional<FlapKnowledge> flaps;
};

/// The mode a command asks for; nothing when its mode is not one of
/// MagneticMode's (a raw enum off the wire can hold any 32-bit value).
inline std::optional<MagneticMode> commandedMode(const msg::ModeCmd& command) {
  const auto mode = static_cast<std::int64_t>(command.mode());
  if (mode < 0 || mode > static_cast<std::int64_t>(MagneticMode::kSpinCapture)) return std::nullopt;
  return static_cast<MagneticMode>(mode);
}

/// The magnetorquers' owner: wheel speeds and the field in, torquer dipole out,
/// in the mode the scenario or flatsat/unloading_mode_cmd sets (unload,
/// detumble, spin capture; MagneticModes). Windows other components request
/// (seed S0's measurements on flatsat/coil_request) hold the coils through the
/// CoilArbiter and are reported on flatsat/coil_window.
class UnloadingControllerNode final : public bus::Component {
 public:
  UnloadingControllerNode(bus::Bus& bus, bus::NodeOptions options,
                          const UnloadingControllerNodeParams& params);

 private:
  void step(const bus::StepContext& ctx) override;
  void receive(const msg::ModeCmd& command);
  /// [N m] K = 2ρA_pV²l with the air's velocity relative to the spacecraft from the onboard orbit.
  double flapScale_Nm(const onboard::ReferenceVectors& reference) const;
  void publishFlaps(const bus::StepContext& ctx, const MagneticModesInput& in, const MagneticModesOutput& out);

  bus::InputOf<bus::topics::kWheelTach>& tach_ = addInput(bus::topics::kWheelTach);
  LastValid<msg::WheelTachReading> last_tach_;  // rides through tachometer dropouts
  bus::InputOf<bus::topics::kMagnetometer>* magnetometer_ = nullptr;    // kMagnetometer
  bus::InputOf<bus::topics::kFieldEstimate>* field_estimate_ = nullptr;  // kFieldFromMomentum
  bus::InputOf<bus::topics::kCoilRequest>* coil_request_ = nullptr;      // kFieldFromMomentum
  bus::InputOf<bus::topics::kAttitudeEstimate>* attitude_ = nullptr;     // kModelAttitude
  bus::WriterOf<bus::topics::kDipoleCmd>& command_ = addOutput(bus::topics::kDipoleCmd);
  bus::WriterOf<bus::topics::kCoilWindow>& coil_window_ = addOutput(bus::topics::kCoilWindow);
  /// Every step, as every topic of a producer: neutral angles (split 255) without flaps or `aero:`.
  bus::WriterOf<bus::topics::kFlapCmd>& flap_cmd_ = addOutput(bus::topics::kFlapCmd);
  std::mutex mode_mutex_;
  std::optional<MagneticMode> requested_mode_;  // received, entered at the next step
  std::vector<std::uint64_t> mode_command_ids_;  // of the commands behind requested_mode_
  bus::CommandAcks acks_{bus_};
  bus::ReaderOf<bus::topics::kUnloadingModeCmd> mode_commands_;
  MagneticModes modes_;
  bus::ParamCommands<MagneticModesParams> param_commands_;
  CoilArbiter arbiter_;
  double quiet_fraction_;
  std::optional<onboard::ReferenceModel> onboard_;
  std::optional<FlapKnowledge> flaps_;
  std::optional<sim::Atmosphere> atmosphere_;
};

/// components.<name>: the unloading keys (gain_per_s, h_*), `mode:`, a
/// `detumble:` and a `spin_capture:` section and the handover; the wheel
/// geometry from spacecraft.wheels, the coil limits from spacecraft.torquers
/// and the orbital rate from the orbit; `field_source: magnetometer | s0_estimate |
/// model_attitude`;
/// the vehicle's onboard view (orbit and field knowledge) for model_attitude
/// and `spin_capture.field_turn: model`; with spacecraft.flaps, an `aero:` section
/// (seed S2: split, max_angle_rad, failed_flaps, drag_only_angle_rad).
UnloadingControllerNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                         const bus::NodeArgs& args, bus::ConfigProblems& problems);

}  // namespace flatsat::unloading_controller
