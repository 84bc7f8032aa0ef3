// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/unloading_controller/AeroAllocation.hpp"
#include "components/unloading_controller/Bdot.hpp"
#include "components/unloading_controller/CrossProductUnloading.hpp"
#include "components/unloading_controller/SpinCapture.hpp"

namespace flatsat::unloading_controller {

/// The coils' three jobs; values as msg::MagneticMode (idl/Modes.idl).
enum class MagneticMode : std::uint8_t { kUnload = 0, kDetumble = 1, kSpinCapture = 2 };

/// "unload", "detumble", "spin_capture" → mode; nullopt for anything else.
std::optional<MagneticMode> magneticModeFromName(const std::string& name);

struct MagneticModesParams {
  CrossProductUnloadingParams unload;  // [-] kUnload's law
  BdotParams detumble;                 // [-] kDetumble's law (ω_ref is ignored: classic B-dot)
  SpinCaptureParams spin;              // [-] kSpinCapture's reference; bang-bang on unload.max_dipole_Am2
  MagneticMode initial_mode = MagneticMode::kUnload;  // [-] mode at reset()
  /// [-] where detumble hands over by itself; nullopt: it stays in detumble.
  std::optional<MagneticMode> after_detumble;
  double handover_rate_rad_s = 0.0035;  // [rad/s] detumble's |P|/|B| below this counts as slow, > 0
  double handover_hold_s = 600.0;       // [s] slow for this long, without a break, hands over, >= 0
  /// [-] kUnload with seed S2's flaps: the law's torque −k H is split between coils and flaps
  /// (its max_dipole_Am2 and min_field_T are the unloading law's); nullopt: coils alone.
  std::optional<AeroAllocationParams> aero;

  /// Every violation as "field: reason"; the unloading law's unprefixed (its keys sit at the
  /// top of the component's section), the others' prefixed "detumble." and "spin_capture.".
  std::vector<std::string> validate() const;
};

/// Onboard orbit and field model at this step (spin capture with FieldTurn::kModel).
struct OnboardField {
  Eigen::Vector3d b_N_T = Eigen::Vector3d::Zero();                    // [T] model field, inertial
  Eigen::Vector3d orbit_normal_N_unit = Eigen::Vector3d::UnitZ();     // [-] r × v / |r × v|, inertial
};

struct MagneticModesInput {
  Eigen::Vector4d wheel_speed_rad_s = Eigen::Vector4d::Zero();  // [rad/s] tachometer speeds (kUnload)
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();              // [T] measured field, body axes
  bool b_valid = false;                                         // field usable
  std::optional<OnboardField> onboard;                          // needed by kSpinCapture with kModel
  double flap_scale_Nm = 0.0;  // [N m] K = 2ρA_pV²l of the flaps now (aero only); <= 0: no air
};

struct MagneticModesOutput {
  MagneticMode mode = MagneticMode::kUnload;              // law that produced m_B_Am2
  Eigen::Vector3d m_B_Am2 = Eigen::Vector3d::Zero();      // [A m²] dipole command
  Eigen::Vector3d h_B_Nms = Eigen::Vector3d::Zero();      // [Nms] excess wheel momentum (kUnload)
  bool active = false;             // a dipole is commanded
  bool saturated = false;          // a coil at (or scaled to) its limit
  bool h_above_start = false;      // kUnload: |H| > h_start_Nms
  bool h_below_stop = false;       // kUnload: |H| < h_stop_Nms
  double rate_error_rad_s = 0.0;   // [rad/s] B-dot modes: |P|/|B|; 0 before the first Ḃ
  bool rate_below_handover = false;  // kDetumble: rate_error_rad_s < handover_rate_rad_s
  bool handover = false;           // detumble handed over by itself this step
  Eigen::Vector3d c_demand_B_Nm = Eigen::Vector3d::Zero();  // [N m] kUnload with aero: −k H when active
  std::optional<AeroAllocationOutput> aero;                 // kUnload with aero: the split and flap angles
};

/// The coils' owner: runs one of cross-product unloading, B-dot detumble or the
/// S4 spin capture (algorithms.md) at a time. A command or the detumble
/// handover restarts the new mode's law, so no stale Ḃ or hysteresis carries over.
/// The handover waits until the rate B-dot sees, |P|/|B| = |ω⊥B| (plus the
/// field's own turn, ~2ω0), has stayed below the threshold for handover_hold_s:
/// |ω⊥B| alone dips whenever ω passes along B, the hold rides over such dips.
class MagneticModes {
 public:
  using Params = MagneticModesParams;
  using Input = MagneticModesInput;
  using Output = MagneticModesOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit MagneticModes(const Params& params);

  /// Back to initial_mode with every law reset.
  void reset();

  /// New unloading gain, thresholds and handover settings, the mode and every law's state
  /// kept (a change in flight); the B-dot laws and the aero split keep their settings.
  /// @throws std::invalid_argument listing every violation of params.validate().
  void retune(const Params& params);

  /// Enters `mode` at the next step (its law reset); the same mode: nothing changes.
  void command(MagneticMode mode);

  /// One control period at t_ns [ns].
  Output step(const Input& in, std::int64_t t_ns);

  MagneticMode mode() const { return mode_; }
  const Params& params() const { return params_; }

 private:
  void enter(MagneticMode mode);

  Params params_;
  CrossProductUnloading unload_;
  Bdot detumble_;
  Bdot spin_;
  std::optional<AeroAllocation> aero_;
  MagneticMode mode_;
  std::optional<std::int64_t> slow_since_ns_;  // detumble: start of the current slow stretch
};

}  // namespace flatsat::unloading_controller
