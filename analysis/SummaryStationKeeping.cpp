// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryStationKeeping.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "bus/Convert.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "components/station_keeping/StationKeepingNode.hpp"
#include "sim/Constants.hpp"
#include "analysis/Conventions.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::analysis {

namespace {

using TruthDef = std::remove_cvref_t<decltype(bus::topics::kTruth)>;
constexpr double kYear_s = 365.25 * 86400.0;

}  // namespace

void summarizeStationKeeping(const bus::Scenario& scenario, const bus::Recording& recording, nlohmann::ordered_json& summary) {
  if (!scenario.hasComponent("station_keeping")) return;
  bus::ConfigProblems ignored;  // the scenario was checked before the run
  const vehicle::Vehicle craft = vehicle::readVehicle(scenario, ignored);
  const auto node = station_keeping::readParams(scenario, craft, {scenario.file, "station_keeping", ""}, ignored);
  double longitude_max = 0.0, inclination_max = 0.0, eccentricity_max = 0.0, last_time_s = 0.0;
  std::optional<msg::TruthState> last;
  recording.forEach(std::string(bus::topics::kTruth.name),
                    [&](std::uint64_t, const std::string&, const std::vector<std::uint8_t>& bytes) {
                      const auto t = bus::deserialize<TruthDef>(bytes);
                      const Eigen::Vector3d r = bus::vec3(t.r_inertial_m()), v = bus::vec3(t.v_inertial_m_s());
                      const double off = std::remainder(t.longitude_rad() - node.planner.station_longitude_rad,
                                                        2.0 * std::numbers::pi);
                      longitude_max = std::max(longitude_max, std::abs(off));
                      const Eigen::Vector3d h = r.cross(v);
                      inclination_max = std::max(inclination_max, std::atan2(std::hypot(h.x(), h.y()), h.z()));
                      const Eigen::Vector3d e = v.cross(h) / sim::kMuEarth_m3_s2 - r.normalized();
                      eccentricity_max = std::max(eccentricity_max, e.norm());
                      last_time_s = 1e-9 * static_cast<double>(t.header().sim_time_ns());
                      last = t;
                    });
  if (!last) return;
  summary["longitude_dev_deg_max"] = longitude_max / kDeg;
  summary["inclination_deg_max"] = inclination_max / kDeg;
  summary["eccentricity_max"] = eccentricity_max;
  double impulse_Ns = 0.0;
  nlohmann::ordered_json firings = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < station_keeping::kGeoThrusters.size(); ++i) {
    impulse_Ns += last->thruster_impulse_total_Ns()[i];
    firings[station_keeping::nameOf(station_keeping::kGeoThrusters[i])] = last->thruster_burns()[i];
  }
  const double dv_m_s = impulse_Ns / node.planner.mass_kg;
  summary["dv_m_s"] = dv_m_s;
  summary["dv_m_s_per_year"] = last_time_s > 0.0 ? dv_m_s * kYear_s / last_time_s : 0.0;
  summary["firings"] = firings;
}

}  // namespace flatsat::analysis
