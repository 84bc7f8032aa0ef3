// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryAeroUnloading.hpp"

#include <cmath>
#include <map>

#include "bus/Convert.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "components/unloading_controller/UnloadingControllerNode.hpp"
#include "sim/Atmosphere.hpp"
#include "sim/Flaps.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::analysis {

namespace {

using TruthDef = std::remove_cvref_t<decltype(bus::topics::kTruth)>;
using FlapDef = std::remove_cvref_t<decltype(bus::topics::kFlapCmd)>;

struct TruthAtStep {
  Eigen::Vector3d b_B_T;
  Eigen::Vector3d tau_flaps_B_Nm;
  double drag_N = 0.0;  // flap force against the air's velocity
};

}  // namespace

void summarizeAeroUnloading(const bus::Scenario& scenario, const bus::Recording& recording, nlohmann::ordered_json& summary) {
  if (!scenario.hasComponent("unloading_controller")) return;
  bus::ConfigProblems ignored;  // the scenario was checked before the run
  const vehicle::Vehicle craft = vehicle::readVehicle(scenario, ignored);
  const auto node = unloading_controller::readParams(scenario, craft, {scenario.file, "unloading_controller", ""}, ignored);
  if (!node.modes.aero) return;
  unloading_controller::AeroAllocationParams alone = *node.modes.aero;
  alone.split = unloading_controller::AeroSplit::kFlapsOnly;
  const unloading_controller::AeroAllocation flaps_alone(alone);
  const sim::FlapWings wings = alone.wings;

  // The truth of step k holds the angles commanded at step k − 1 over [t_k−1, t_k]; the
  // command of step k acts on the next. Pair each command with the truth that shows it.
  std::map<std::uint64_t, TruthAtStep> truth;
  recording.forEach(std::string(bus::topics::kTruth.name),
                    [&](std::uint64_t step, const std::string&, const std::vector<std::uint8_t>& bytes) {
                      const auto t = bus::deserialize<TruthDef>(bytes);
                      const Eigen::Quaterniond q_NB = bus::quat(t.q_inertial_body());
                      const Eigen::Vector3d motion_B =
                          q_NB.conjugate() *
                          sim::velocityThroughAir_N_m_s(bus::vec3(t.r_inertial_m()), bus::vec3(t.v_inertial_m_s()))
                              .normalized();
                      truth[step] = {bus::vec3(t.b_body_T()), bus::vec3(t.tau_flaps_body_Nm()),
                                     -bus::vec3(t.f_flaps_body_N()).dot(motion_B)};
                    });
  double aero = 0.0, along_B = 0.0, least = 0.0, drag = 0.0, drag_alone = 0.0, delivered = 0.0, plant_drag = 0.0;
  std::uint64_t commands = 0;
  std::uint64_t demands = 0;
  double flap_error2 = 0.0;  // Σ (relative flap torque error)²
  std::uint64_t flap_demands = 0;
  recording.forEach(std::string(bus::topics::kFlapCmd.name),
                    [&](std::uint64_t step, const std::string&, const std::vector<std::uint8_t>& bytes) {
                      const auto cmd = bus::deserialize<FlapDef>(bytes);
                      const auto shown = truth.find(step + 1);
                      if (shown == truth.end()) return;
                      const Eigen::Vector3d C = bus::vec3(cmd.c_demand_body_Nm());
                      const Eigen::Vector3d& B = shown->second.b_B_T;
                      ++commands;
                      plant_drag += shown->second.drag_N;
                      if (C.isZero(0.0) || B.isZero(0.0)) return;
                      ++demands;
                      delivered += cmd.delivered();
                      aero += shown->second.tau_flaps_B_Nm.norm();
                      along_B += std::abs(C.dot(B)) / B.norm();
                      // With B all but normal to the flaps' plane no flap torque completes C:
                      // such steps count for neither ratio's floor.
                      const double plant_in_plane = unloading_controller::fieldInFlapPlane_B(B, wings).norm();
                      least += plant_in_plane >= node.modes.aero->min_field_T ? std::abs(C.dot(B)) / plant_in_plane
                                                                              : std::abs(C.dot(B)) / B.norm();
                      const double K = cmd.flap_scale_Nm();
                      drag += K * unloading_controller::FlapInversion::dragShape(bus::vec4(cmd.theta_rad()));
                      // The flaps' share the split asked for (eq. II), as delivered, against the
                      // torque the commanded angles give by the seed's shapes: the inversion's error.
                      const Eigen::Vector3d b_law = bus::vec3(cmd.b_body_T());  // the field the split used
                      const double in_plane = unloading_controller::fieldInFlapPlane_B(b_law, wings).norm();
                      const double min_field_T = node.modes.aero->min_field_T;  // below it the split gives no flaps
                      if (K > 0.0 && in_plane >= min_field_T) {
                        const Eigen::Vector3d wanted =
                            cmd.delivered() * unloading_controller::leastFlapTorque_B_Nm(C, b_law, wings);
                        const Eigen::Vector2d c = sim::Flaps::normalisedTorques(bus::vec4(cmd.theta_rad()));
                        if (wanted.norm() > 0.0) {
                          flap_error2 += (K * sim::flapTorqueShape_B(c, wings) - wanted).squaredNorm() / wanted.squaredNorm();
                          ++flap_demands;
                        }
                      }
                      const auto other = flaps_alone.step({C, bus::vec3(cmd.b_body_T()), K}, 0);
                      drag_alone += K * unloading_controller::FlapInversion::dragShape(other.flaps.theta_rad);
                    });
  if (commands == 0) return;
  summary["aero_torque_ratio"] = along_B > 0 ? aero / along_B : 0.0;
  summary["aero_torque_ratio_least"] = along_B > 0 ? least / along_B : 0.0;
  summary["drag_ratio"] = drag_alone > 0 ? drag / drag_alone : 0.0;
  summary["flap_drag_N_mean"] = plant_drag / static_cast<double>(commands);
  summary["torque_delivered_mean"] = demands > 0 ? delivered / static_cast<double>(demands) : 0.0;
  if (node.modes.aero->split == unloading_controller::AeroSplit::kMagneticAero && flap_demands > 0) {
    summary["flap_torque_error_pct_rms"] = 100.0 * std::sqrt(flap_error2 / static_cast<double>(flap_demands));
  }
}

}  // namespace flatsat::analysis
