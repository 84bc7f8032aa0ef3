// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryStationKeeping.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "bus/Convert.hpp"
#include "components/station_keeping/StationKeepingNode.hpp"
#include "sim/Constants.hpp"
#include "analysis/Conventions.hpp"

namespace flatsat::analysis {

namespace {

constexpr double kYear_s = 365.25 * 86400.0;

}  // namespace

StationKeepingFigures::StationKeepingFigures(const bus::Scenario& scenario, const vehicle::Vehicle& craft) {
  if (!scenario.hasComponent("station_keeping")) return;
  bus::ConfigProblems ignored;  // the scenario was checked before the run
  const auto node = station_keeping::readParams(scenario, craft, {scenario.file, "station_keeping", ""}, ignored);
  active_ = true;
  station_longitude_rad_ = node.planner.station_longitude_rad;
  mass_kg_ = node.planner.mass_kg;
}

void StationKeepingFigures::addTruth(const TruthSample& t) {
  if (!active_) return;
  const Eigen::Vector3d r = bus::vec3(t.r_inertial_m()), v = bus::vec3(t.v_inertial_m_s());
  const double off = std::remainder(t.longitude_rad() - station_longitude_rad_, 2.0 * std::numbers::pi);
  longitude_max_ = std::max(longitude_max_, std::abs(off));
  const Eigen::Vector3d h = r.cross(v);
  inclination_max_ = std::max(inclination_max_, std::atan2(std::hypot(h.x(), h.y()), h.z()));
  const Eigen::Vector3d e = v.cross(h) / sim::kMuEarth_m3_s2 - r.normalized();
  eccentricity_max_ = std::max(eccentricity_max_, e.norm());
  last_time_s_ = 1e-9 * static_cast<double>(t.header().sim_time_ns());
  last_ = t;
}

void StationKeepingFigures::summarize(nlohmann::ordered_json& summary) const {
  if (!last_) return;
  summary["longitude_dev_deg_max"] = longitude_max_ / kDeg;
  summary["inclination_deg_max"] = inclination_max_ / kDeg;
  summary["eccentricity_max"] = eccentricity_max_;
  double impulse_Ns = 0.0;
  nlohmann::ordered_json firings = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < station_keeping::kGeoThrusters.size(); ++i) {
    impulse_Ns += last_->thruster_impulse_total_Ns()[i];
    firings[station_keeping::nameOf(station_keeping::kGeoThrusters[i])] = last_->thruster_burns()[i];
  }
  const double dv_m_s = impulse_Ns / mass_kg_;
  summary["dv_m_s"] = dv_m_s;
  summary["dv_m_s_per_year"] = last_time_s_ > 0.0 ? dv_m_s * kYear_s / last_time_s_ : 0.0;
  summary["firings"] = firings;
}

}  // namespace flatsat::analysis
