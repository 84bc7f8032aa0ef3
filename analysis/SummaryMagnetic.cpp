// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryMagnetic.hpp"

#include "bus/Convert.hpp"
#include "components/unloading_controller/UnloadingControllerNode.hpp"
#include "analysis/MagneticMetrics.hpp"

namespace flatsat::analysis {

namespace {

nlohmann::ordered_json orNull(const std::optional<double>& value) {
  return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

}  // namespace

MagneticFigures::MagneticFigures(const bus::Scenario& scenario, const vehicle::Vehicle& craft) {
  using unloading_controller::MagneticMode;
  if (!scenario.hasComponent("unloading_controller")) return;
  bus::ConfigProblems ignored;  // the scenario was checked before the run
  const auto control =
      unloading_controller::readParams(scenario, craft, {scenario.file, "unloading_controller", ""}, ignored).modes;
  spin_ = control.initial_mode == MagneticMode::kSpinCapture || control.after_detumble == MagneticMode::kSpinCapture;
  if (control.initial_mode == MagneticMode::kUnload) return;
  MagneticMetricsParams judge;
  judge.max_dipole_Am2 = control.unload.max_dipole_Am2;
  if (spin_) {
    judge.spin_axis_B = control.spin.spin_axis_B;
    judge.spin_rate_rad_s = control.spin.restRate_rad_s();
  }
  metrics_.emplace(judge);
}

void MagneticFigures::addTruth(const TruthSample& t) {
  if (!metrics_) return;
  metrics_->add(static_cast<double>(t.header().sim_time_ns()) * 1e-9, bus::quat(t.q_inertial_body()),
                bus::vec3(t.w_body_rad_s()), bus::vec3(t.r_inertial_m()), bus::vec3(t.v_inertial_m_s()),
                bus::vec3(t.dipole_body_Am2()));
}

void MagneticFigures::summarize(nlohmann::ordered_json& summary) const {
  if (!metrics_) return;
  const auto r = metrics_->result();
  summary["rate_deg_s_final"] = r.rate_deg_s_final;
  summary["time_to_detumble_s"] = orNull(r.time_to_detumble_s);
  if (spin_) {
    summary["spin_axis_error_deg"] = r.spin_axis_error_deg;
    summary["spin_rate_error_pct"] = r.spin_rate_error_pct;
    summary["time_to_capture_s"] = orNull(r.time_to_capture_s);
  }
  summary["coil_duty"] = r.coil_duty;
}

}  // namespace flatsat::analysis
