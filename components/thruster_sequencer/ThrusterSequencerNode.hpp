// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>

#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/thruster_sequencer/AngleOnlySequencer.hpp"
#include "components/thruster_sequencer/GimbalDumping.hpp"
#include "components/thruster_sequencer/StationKeepingFirings.hpp"
#include "components/thruster_sequencer/ThrusterMomentumDumping.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::thruster_sequencer {

/// What the sequencer does; each mode reads its own input only.
struct ThrusterSequencerParams {
  enum class Mode { kAngleOnly, kMomentumDumping, kStationKeeping };
  Mode mode = Mode::kAngleOnly;               // [-] `mode: angle_only | momentum_dumping | station_keeping`
  AngleOnlySequencerParams angle_only;        // [-] used in kAngleOnly (see there)
  ThrusterMomentumDumpingParams dumping;      // [-] used in kMomentumDumping (see there)
  StationKeepingFiringsParams station_keeping;  // [-] used in kStationKeeping (see there)
  std::optional<GimbalDumpingParams> gimbal_dumping;  // [-] kStationKeeping with wheels and a wheel_tach: MD firings dump
};

/// Thruster on-times on the bus. angle_only (seed S1): the Sun sensor's reading is the only
/// input; no rate of any kind (gyro, estimate) is read, the angle-only law needs none.
/// momentum_dumping: the wheel tachometers only; the attitude controller holds the attitude.
/// station_keeping (seed S3): flatsat/station_keeping_plan's firings as finite burns, at
/// the right ascension of flatsat/truth's position (standing in for orbit determination);
/// the plant's thrusters are the seed's six in numbering order (20, 22, ... 30). With
/// wheels and a wheel_tach in the rig, the firings Table I gives to momentum dumping
/// turn their gimbals against the tachometers' stored momentum (GimbalDumping).
class ThrusterSequencerNode final : public bus::Component {
 public:
  ThrusterSequencerNode(bus::Bus& bus, bus::NodeOptions options, const ThrusterSequencerParams& params);

 private:
  void step(const bus::StepContext& ctx) override;
  /// The limit cycle's phase and counts (claim 4's n) or the dump under way with the
  /// last valid wheel speeds, and the on-times still owed: a restarted sequencer goes
  /// on with the correction it was in. Station keeping keeps nothing: a restarted
  /// sequencer takes the plan in force anew (a burn under way is cut short).
  nlohmann::json saveState() const override;
  void restoreState(const nlohmann::json& state) override;

  bus::WriterOf<bus::topics::kThrusterCmd>& command_ = addOutput(bus::topics::kThrusterCmd);
  bus::InputOf<bus::topics::kSunSensor>* sun_ = nullptr;   // angle_only
  bus::InputOf<bus::topics::kWheelTach>* tach_ = nullptr;  // momentum_dumping
  bus::InputOf<bus::topics::kStationKeepingPlan>* plan_ = nullptr;  // station_keeping
  bus::InputOf<bus::topics::kTruth>* truth_ = nullptr;              // station_keeping
  std::size_t thruster_count_;
  std::optional<AngleOnlySequencer> sequencer_;
  std::optional<ThrusterMomentumDumping> dumping_;
  std::optional<StationKeepingFirings> firings_;
  std::optional<GimbalDumping> gimbal_dumping_;
  double step_s_ = 0.0;  // station_keeping: [s] the step the on-times fill
  Eigen::Vector4d last_speed_rad_s_ = Eigen::Vector4d::Zero();  // rides through tachometer dropouts
};

/// components.<name>: the mode and its parameters; the thrusters, inertia, wheels and
/// the Sun sensor's boresight from the vehicle's onboard view, the step from step_s and
/// the rate divider.
ThrusterSequencerParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                   const bus::NodeArgs& args, bus::ConfigProblems& problems);

}  // namespace flatsat::thruster_sequencer
