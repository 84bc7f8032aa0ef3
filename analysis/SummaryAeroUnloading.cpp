// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryAeroUnloading.hpp"

#include <cmath>

#include "bus/Convert.hpp"
#include "sim/Atmosphere.hpp"
#include "sim/Flaps.hpp"

namespace flatsat::analysis {

AeroUnloadingFigures::AeroUnloadingFigures(const bus::Scenario& scenario, const vehicle::Vehicle& craft) {
  if (!scenario.hasComponent("unloading_controller")) return;
  bus::ConfigProblems ignored;  // the scenario was checked before the run
  const auto node = unloading_controller::readParams(scenario, craft, {scenario.file, "unloading_controller", ""}, ignored);
  if (!node.modes.aero) return;
  aero_ = *node.modes.aero;
  unloading_controller::AeroAllocationParams alone = *aero_;
  alone.split = unloading_controller::AeroSplit::kFlapsOnly;
  flaps_alone_.emplace(alone);
}

// The truth of step k holds the angles commanded at step k − 1 over [t_k−1, t_k]; the
// command of step k acts on the next: each command is paired with the truth of k + 1.
void AeroUnloadingFigures::addTruth(std::uint64_t step, const TruthSample& t) {
  if (!aero_) return;
  const Eigen::Quaterniond q_NB = bus::quat(t.q_inertial_body());
  const Eigen::Vector3d motion_B =
      q_NB.conjugate() *
      sim::velocityThroughAir_N_m_s(bus::vec3(t.r_inertial_m()), bus::vec3(t.v_inertial_m_s())).normalized();
  pairs_.addReference(step,
                      {bus::vec3(t.b_body_T()), bus::vec3(t.tau_flaps_body_Nm()),
                       -bus::vec3(t.f_flaps_body_N()).dot(motion_B)},
                      [this](std::uint64_t, const TruthAtStep& shown, const FlapCmdSample& cmd) { judge(shown, cmd); });
}

void AeroUnloadingFigures::addFlapCmd(std::uint64_t step, const FlapCmdSample& cmd) {
  if (!aero_) return;
  pairs_.addSample(step + 1, cmd,
                   [this](std::uint64_t, const TruthAtStep& shown, const FlapCmdSample& c) { judge(shown, c); });
}

void AeroUnloadingFigures::judge(const TruthAtStep& shown, const FlapCmdSample& cmd) {
  const sim::FlapWings& wings = aero_->wings;
  const Eigen::Vector3d C = bus::vec3(cmd.c_demand_body_Nm());
  const Eigen::Vector3d& B = shown.b_B_T;
  ++commands_;
  plant_drag_ += shown.drag_N;
  if (C.isZero(0.0) || B.isZero(0.0)) return;
  ++demands_;
  delivered_ += cmd.delivered();
  aero_sum_ += shown.tau_flaps_B_Nm.norm();
  along_B_ += std::abs(C.dot(B)) / B.norm();
  // With B all but normal to the flaps' plane no flap torque completes C:
  // such steps count for neither ratio's floor.
  const double plant_in_plane = unloading_controller::fieldInFlapPlane_B(B, wings).norm();
  least_ += plant_in_plane >= aero_->min_field_T ? std::abs(C.dot(B)) / plant_in_plane : std::abs(C.dot(B)) / B.norm();
  const double K = cmd.flap_scale_Nm();
  drag_ += K * unloading_controller::FlapInversion::dragShape(bus::vec4(cmd.theta_rad()));
  // The flaps' share the split asked for (eq. II), as delivered, against the
  // torque the commanded angles give by the seed's shapes: the inversion's error.
  const Eigen::Vector3d b_law = bus::vec3(cmd.b_body_T());  // the field the split used
  const double in_plane = unloading_controller::fieldInFlapPlane_B(b_law, wings).norm();
  if (K > 0.0 && in_plane >= aero_->min_field_T) {  // below it the split gives no flaps
    const Eigen::Vector3d wanted = cmd.delivered() * unloading_controller::leastFlapTorque_B_Nm(C, b_law, wings);
    const Eigen::Vector2d c = sim::Flaps::normalisedTorques(bus::vec4(cmd.theta_rad()));
    if (wanted.norm() > 0.0) {
      flap_error2_ += (K * sim::flapTorqueShape_B(c, wings) - wanted).squaredNorm() / wanted.squaredNorm();
      ++flap_demands_;
    }
  }
  const auto other = flaps_alone_->step({C, b_law, K}, 0);
  drag_alone_ += K * unloading_controller::FlapInversion::dragShape(other.flaps.theta_rad);
}

void AeroUnloadingFigures::summarize(nlohmann::ordered_json& summary) const {
  if (commands_ == 0) return;
  summary["aero_torque_ratio"] = along_B_ > 0 ? aero_sum_ / along_B_ : 0.0;
  summary["aero_torque_ratio_least"] = along_B_ > 0 ? least_ / along_B_ : 0.0;
  summary["drag_ratio"] = drag_alone_ > 0 ? drag_ / drag_alone_ : 0.0;
  summary["flap_drag_N_mean"] = plant_drag_ / static_cast<double>(commands_);
  summary["torque_delivered_mean"] = demands_ > 0 ? delivered_ / static_cast<double>(demands_) : 0.0;
  if (aero_->split == unloading_controller::AeroSplit::kMagneticAero && flap_demands_ > 0) {
    summary["flap_torque_error_pct_rms"] = 100.0 * std::sqrt(flap_error2_ / static_cast<double>(flap_demands_));
  }
}

}  // namespace flatsat::analysis
