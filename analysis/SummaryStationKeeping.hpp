// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>

#include <nlohmann/json.hpp>

#include "analysis/TruthSample.hpp"
#include "bus/Scenario.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::analysis {

/// Seed S3 keys of summary.json, when a station_keeping planner is in
/// the rig, from the truth of every recorded step:
///  - longitude_dev_deg_max: the longitude's largest distance from the station;
///  - inclination_deg_max: the largest osculating inclination (r × v);
///  - eccentricity_max: the largest osculating eccentricity (two-body, r and v);
///  - dv_m_s, dv_m_s_per_year: the six thrusters' impulse over the mass, over the
///    run and scaled to 365.25 days (the truth's running totals: exact in a
///    recording decimated in time);
///  - firings: burns begun per thruster, {"NW(20)": n, ...}.
class StationKeepingFigures {
 public:
  StationKeepingFigures(const bus::Scenario& scenario, const vehicle::Vehicle& craft);
  void addTruth(const TruthSample& truth);
  void summarize(nlohmann::ordered_json& summary) const;

 private:
  bool active_ = false;
  double station_longitude_rad_ = 0.0, mass_kg_ = 0.0;
  double longitude_max_ = 0.0, inclination_max_ = 0.0, eccentricity_max_ = 0.0, last_time_s_ = 0.0;
  std::optional<TruthSample> last_;
};

}  // namespace flatsat::analysis
