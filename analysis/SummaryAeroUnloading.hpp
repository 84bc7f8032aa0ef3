// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "analysis/StepPairs.hpp"
#include "analysis/TruthSample.hpp"
#include "bus/Scenario.hpp"
#include "components/unloading_controller/UnloadingControllerNode.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::analysis {

/// Seed S2 keys of summary.json, when the unloading controller splits its
/// torque with the flaps (`aero:`), from flatsat/flap_cmd and the truth that shows it:
///  - aero_torque_ratio: Σ|flap torque (plant)| / Σ|C·B̂|, C the torque the law asked for and
///    B the plant's field: the flaps' torque against the component of C along B. No flap
///    torque in the flaps' plane (roll–yaw, or roll–pitch with the wings along z) that
///    completes C can go below aero_torque_ratio_least, Σ|C·B|/|B in that plane| / Σ|C·B̂|,
///    1 when B lies in the plane.
///  - drag_ratio: the flaps' drag over the run, K Σ|sin θi|³ summed over the steps, against
///    what the flaps-alone split (their plane's part from the flaps, AeroSplit::kFlapsOnly) would
///    have needed for the same demands, field and air: < 1 is less drag than flaps alone.
///  - flap_drag_N_mean: the plant's flap force against the air's velocity, mean over the run.
///  - torque_delivered_mean: mean share of the demand delivered (limits scale it down).
///  - flap_torque_error_pct_rms (split magnetic_aero): the flaps' share of the demand
///    (eq. II, on the field the law used, times the share delivered) against K·(c_ax, c_az)
///    of the commanded angles by the seed's shapes: the flap solver's own error, RMS over
///    the steps with a demand.
class AeroUnloadingFigures {
 public:
  AeroUnloadingFigures(const bus::Scenario& scenario, const vehicle::Vehicle& craft);
  void addTruth(std::uint64_t step, const TruthSample& truth);
  void addFlapCmd(std::uint64_t step, const FlapCmdSample& cmd);
  void summarize(nlohmann::ordered_json& summary) const;

 private:
  struct TruthAtStep {
    Eigen::Vector3d b_B_T;
    Eigen::Vector3d tau_flaps_B_Nm;
    double drag_N = 0.0;  // flap force against the air's velocity
  };
  void judge(const TruthAtStep& shown, const FlapCmdSample& cmd);
  std::optional<unloading_controller::AeroAllocationParams> aero_;  // none: no flaps in the rig
  std::optional<unloading_controller::AeroAllocation> flaps_alone_;
  StepPairs<TruthAtStep, FlapCmdSample> pairs_;
  double aero_sum_ = 0.0, along_B_ = 0.0, least_ = 0.0, drag_ = 0.0, drag_alone_ = 0.0, delivered_ = 0.0,
         plant_drag_ = 0.0;
  std::uint64_t commands_ = 0, demands_ = 0;
  double flap_error2_ = 0.0;  // Σ (relative flap torque error)²
  std::uint64_t flap_demands_ = 0;
};

}  // namespace flatsat::analysis
