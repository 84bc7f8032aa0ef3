// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryMagnetic.hpp"

#include "bus/Convert.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "components/unloading_controller/UnloadingControllerNode.hpp"
#include "analysis/MagneticMetrics.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::analysis {

namespace {

nlohmann::ordered_json orNull(const std::optional<double>& value) {
  return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

}  // namespace

void summarizeMagnetic(const bus::Scenario& scenario, const bus::Recording& recording,
                       nlohmann::ordered_json& summary) {
  using unloading_controller::MagneticMode;
  if (!scenario.hasComponent("unloading_controller")) return;
  bus::ConfigProblems ignored;  // the scenario was checked before the run
  const vehicle::Vehicle craft = vehicle::readVehicle(scenario, ignored);
  const auto control =
      unloading_controller::readParams(scenario, craft, {scenario.file, "unloading_controller", ""}, ignored).modes;
  const bool spin = control.initial_mode == MagneticMode::kSpinCapture ||
                    control.after_detumble == MagneticMode::kSpinCapture;
  if (control.initial_mode == MagneticMode::kUnload) return;

  MagneticMetricsParams judge;
  judge.max_dipole_Am2 = control.unload.max_dipole_Am2;
  if (spin) {
    judge.spin_axis_B = control.spin.spin_axis_B;
    judge.spin_rate_rad_s = control.spin.restRate_rad_s();
  }
  MagneticMetrics metrics(judge);
  using TruthDef = std::remove_cvref_t<decltype(bus::topics::kTruth)>;
  recording.forEach(std::string(bus::topics::kTruth.name),
                    [&](std::uint64_t, const std::string&, const std::vector<std::uint8_t>& bytes) {
                      const auto t = bus::deserialize<TruthDef>(bytes);
                      metrics.add(static_cast<double>(t.header().sim_time_ns()) * 1e-9, bus::quat(t.q_inertial_body()),
                                  bus::vec3(t.w_body_rad_s()), bus::vec3(t.r_inertial_m()),
                                  bus::vec3(t.v_inertial_m_s()), bus::vec3(t.dipole_body_Am2()));
                    });
  const auto r = metrics.result();
  summary["rate_deg_s_final"] = r.rate_deg_s_final;
  summary["time_to_detumble_s"] = orNull(r.time_to_detumble_s);
  if (spin) {
    summary["spin_axis_error_deg"] = r.spin_axis_error_deg;
    summary["spin_rate_error_pct"] = r.spin_rate_error_pct;
    summary["time_to_capture_s"] = orNull(r.time_to_capture_s);
  }
  summary["coil_duty"] = r.coil_duty;
}

}  // namespace flatsat::analysis
