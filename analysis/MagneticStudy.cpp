// SPDX-License-Identifier: Apache-2.0
#include "analysis/MagneticStudy.hpp"

#include <algorithm>
#include <string>

#include "components/dynamics_server/DynamicsServerParams.hpp"
#include "components/magnetometer/MagnetometerNode.hpp"
#include "components/unloading_controller/UnloadingControllerNode.hpp"
#include "sim/DynamicsModel.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::analysis {
namespace {

std::uint32_t dividerOf(const bus::Scenario& scenario, const std::string& name) {
  for (const auto& c : scenario.components) {
    if (c.name == name) return c.rate_divider;
  }
  return 1;
}

}  // namespace

/// One seed: the rig's dataflow in one process. At step k the magnetometer
/// samples truth(k), the controller answers from that sample, and the dipole is
/// held over [k, k+1) — as the lockstep rig does.
MagneticCase runMagneticCase(bus::Scenario scenario, std::uint64_t seed) {
  scenario.seed = seed;
  bus::ConfigProblems problems;
  const vehicle::Vehicle craft = vehicle::readVehicle(scenario, problems);
  const auto server = dynamics_server::readParams(scenario, craft, {scenario.file, "dynamics_server", ""}, problems);
  const auto node = unloading_controller::readParams(scenario, craft, {scenario.file, "unloading_controller", ""}, problems);
  const auto& control = node.modes;
  const auto sensor = magnetometer::readParams(scenario, {scenario.file, "magnetometer", ""}, problems);
  if (!problems.empty()) throw std::invalid_argument(problems.joined());

  sim::DynamicsModel model(server.dynamics);
  magnetometer::MagnetometerModel field_sensor(sensor.model);
  unloading_controller::MagneticModes modes(control);
  std::optional<onboard::ReferenceModel> onboard;
  if (node.onboard) onboard.emplace(*node.onboard);
  MagneticMetricsParams judge;
  judge.max_dipole_Am2 = control.unload.max_dipole_Am2;
  const bool spin = control.initial_mode == unloading_controller::MagneticMode::kSpinCapture ||
                    control.after_detumble == unloading_controller::MagneticMode::kSpinCapture;
  if (spin) {
    judge.spin_axis_B = control.spin.spin_axis_B;
    judge.spin_rate_rad_s = control.spin.restRate_rad_s();
  }
  MagneticMetrics metrics(judge);
  const std::uint32_t sensor_divider = dividerOf(scenario, "magnetometer");
  const std::uint32_t control_divider = dividerOf(scenario, "unloading_controller");

  MagneticCase result;
  result.orbit_period_s = server.orbit_period_s;
  magnetometer::MagnetometerOutput reading;
  sim::ActuatorCommands cmd;
  for (std::uint64_t k = 0; k < server.final_step; ++k) {
    const sim::Truth& truth = model.truth();
    if (k % sensor_divider == 0) reading = field_sensor.step({truth.b_B_T}, truth.t);
    if (k % control_divider == 0) {
      unloading_controller::MagneticModesInput in{truth.wheel_speed_rad_s, reading.b_B_T, !reading.saturated, std::nullopt};
      if (onboard) {
        const auto reference = onboard->step(truth.t);
        in.onboard = unloading_controller::OnboardField{reference.b_N_T, reference.orbit_normal_N_unit};
      }
      const auto out = modes.step(in, truth.t);
      cmd.dipole_B_Am2 = out.m_B_Am2;
      if (out.handover) result.handover_s = sim::toSeconds(truth.t);
    }
    model.step(cmd, truth.t + server.step_period_ns);
    const sim::Truth& after = model.truth();
    metrics.add(sim::toSeconds(after.t), after.q_NB, after.w_NB_B_rad_s, after.r_N_m, after.v_N_m_s,
                after.dipole_applied_B_Am2);
    const double orbits = sim::toSeconds(after.t) / server.orbit_period_s;
    if (orbits >= 4.0 && orbits <= 5.0) {
      const auto now = metrics.result();
      result.fifth_orbit_axis_deg = std::max(result.fifth_orbit_axis_deg, now.spin_axis_error_deg);
      result.fifth_orbit_rate_pct = std::max(result.fifth_orbit_rate_pct, now.spin_rate_error_pct);
    }
  }
  result.metrics = metrics.result();
  return result;
}

}  // namespace flatsat::analysis
