// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>

#include <nlohmann/json.hpp>

#include "analysis/MagneticMetrics.hpp"
#include "analysis/TruthSample.hpp"
#include "bus/Scenario.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::analysis {

/// Detumble and spin-capture keys of summary.json, from the truth of every
/// recorded step, when the unloading controller starts in detumble or
/// spin_capture: rate_deg_s_final, time_to_detumble_s (null: not below
/// 0.2 deg/s at the end), coil_duty, and with spin capture
/// spin_axis_error_deg, spin_rate_error_pct, time_to_capture_s
/// (MagneticMetrics). Other scenarios: nothing added.
class MagneticFigures {
 public:
  MagneticFigures(const bus::Scenario& scenario, const vehicle::Vehicle& craft);
  void addTruth(const TruthSample& truth);
  void summarize(nlohmann::ordered_json& summary) const;

 private:
  bool spin_ = false;
  std::optional<MagneticMetrics> metrics_;  // none: not a detumble or spin-capture rig
};

}  // namespace flatsat::analysis
