// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <nlohmann/json.hpp>

#include "bus/Recording.hpp"
#include "bus/Scenario.hpp"

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
void summarizeStationKeeping(const bus::Scenario& scenario, const bus::Recording& recording, nlohmann::ordered_json& summary);

}  // namespace flatsat::analysis
