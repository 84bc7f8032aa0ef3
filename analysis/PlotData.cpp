// SPDX-License-Identifier: Apache-2.0
#include "analysis/PlotData.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <Eigen/Geometry>

#include "bus/Convert.hpp"
#include "bus/Recording.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "components/attitude_controller/AttitudeControllerNode.hpp"
#include "analysis/Conventions.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::analysis {

namespace {

constexpr double kTeslaToMicro = 1e6;

template <const auto& Topic>
using DefOf = std::remove_cvref_t<decltype(Topic)>;

/// Measurement validity, when the reading carries it (dropouts).
template <class Sample>
bool isValid(const Sample& s) {
  if constexpr (requires { s.valid(); }) {
    return s.valid();
  } else {
    return true;
  }
}

double angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

template <const auto& Topic, class Visit>
void forEachSample(const bus::Recording& recording, Visit&& visit) {
  recording.forEach(std::string(Topic.name),
                    [&](std::uint64_t step, const std::string&, const std::vector<std::uint8_t>& bytes) {
                      visit(step, bus::deserialize<DefOf<Topic>>(bytes));
                    });
}

double seconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }

}  // namespace

PlotContext readPlotContext(const std::string& scenario_file) {
  PlotContext c;
  if (scenario_file.empty() || !std::filesystem::exists(scenario_file)) return c;
  const auto scenario = bus::loadScenario(scenario_file);
  bus::ConfigProblems ignored;  // the run checked its scenario; what fails stays unset
  const vehicle::Vehicle craft = vehicle::readVehicle(scenario, ignored);
  const auto& plant = craft.truth;
  c.epoch = plant.epoch;
  c.acquisition_s = scenario.acquisition_s;
  if (plant.body.wheel_count > 0) {
    c.wheel_capacity_Nms = plant.body.wheel_max_momentum_Nms.head(plant.body.wheel_count).minCoeff();
  }
  if (plant.torquer_max_dipole_Am2.minCoeff() > 0) c.max_dipole_Am2 = plant.torquer_max_dipole_Am2;
  if (scenario.hasComponent("attitude_controller")) {
    const Eigen::Vector3d axis =
        attitude_controller::readParams(scenario, craft, {scenario.file, "attitude_controller", ""}, ignored)
            .law.pointing_axis_B;
    if (axis.norm() > 0) c.pointing_axis_B = axis.normalized();
  }
  return c;
}

PlotData readPlotData(const std::string& recording_path, const PlotContext& context) {
  const bus::Recording recording(recording_path, bus::Recording::Access::kRead);
  PlotData d;
  struct TruthAtStep {
    Eigen::Quaterniond q_NB;
    Eigen::Vector3d b_N_T, b_B_T;
  };
  std::map<std::uint64_t, TruthAtStep> truth_by_step;
  const double jd0 = context.epoch ? sim::julianDate(*context.epoch) : 0.0;
  // Generic (auto) so that `requires` below tests the generated type.
  forEachSample<bus::topics::kTruth>(recording, [&](std::uint64_t step, const auto& s) {
    TruthRow r{};
    r.t_s = seconds(s.header().sim_time_ns());
    const Eigen::Quaterniond q_NB = bus::quat(s.q_inertial_body()).normalized();
    r.pointing_error_deg =
        angle(q_NB * context.pointing_axis_B, bus::vec3(s.sun_inertial_unit())) * kRadToDeg;
    r.w_B_deg_s = bus::vec3(s.w_body_rad_s()) * kRadToDeg;
    r.wheel_rad_s = s.wheel_speed_rad_s();
    r.h_wheels_Nms = bus::vec3(s.h_wheels_body_Nms()).norm();
    r.b_B_uT = bus::vec3(s.b_body_T()) * kTeslaToMicro;
    r.dipole_B_Am2 = bus::vec3(s.dipole_body_Am2());
    r.illumination = s.illumination();
    if constexpr (requires { s.latitude_rad(); s.longitude_rad(); }) {
      // The dynamics server's own geodetic sub-satellite point (WGS-84).
      r.lat_deg = s.latitude_rad() * kRadToDeg;
      r.lon_deg = s.longitude_rad() * kRadToDeg;
      d.track = PlotData::Track::kGeodetic;
    } else if (context.epoch) {
      // Earth-fixed position: GMST rotation only (sim/Time.hpp R_EN); spherical Earth.
      const Eigen::Vector3d r_E =
          sim::R_EN(jd0 + r.t_s / sim::kSecondsPerDay) * bus::vec3(s.r_inertial_m());
      r.lat_deg = std::asin(r_E.z() / r_E.norm()) * kRadToDeg;
      r.lon_deg = std::atan2(r_E.y(), r_E.x()) * kRadToDeg;
      d.track = PlotData::Track::kGeocentric;
    }
    d.wheel_count = std::min<std::size_t>(s.wheel_count(), 4);
    d.truth.push_back(r);
    truth_by_step[step] = {q_NB, bus::vec3(s.b_inertial_T()), bus::vec3(s.b_body_T())};
  });
  forEachSample<bus::topics::kMagnetometer>(
      recording, [&](std::uint64_t step, const msg::MagnetometerReading& s) {
        const auto truth = truth_by_step.find(step);
        if (!isValid(s) || truth == truth_by_step.end()) return;
        const Eigen::Vector3d b_B = bus::vec3(s.b_body_T());
        d.magnetometer.push_back({seconds(s.header().sim_time_ns()), b_B * kTeslaToMicro,
                                  (b_B - truth->second.b_B_T) * 1e9});
      });
  forEachSample<bus::topics::kAttitudeEstimate>(
      recording, [&](std::uint64_t step, const msg::AttitudeEstimate& s) {
        const auto truth = truth_by_step.find(step);
        if (!s.initialized() || truth == truth_by_step.end()) return;
        const Eigen::Quaterniond q_est = bus::quat(s.q_inertial_body()).normalized();
        // Error rotation, body axes of the truth: q_err = q_true^-1 q_est.
        Eigen::Quaterniond q_err = truth->second.q_NB.conjugate() * q_est;
        if (q_err.w() < 0) q_err.coeffs() *= -1.0;
        EstimateRow r{};
        r.t_s = seconds(s.header().sim_time_ns());
        r.error_deg = 2.0 * std::atan2(q_err.vec().norm(), q_err.w()) * kRadToDeg;
        r.error_B_deg = 2.0 * q_err.vec() * kRadToDeg;
        r.b_B_uT = (q_est.conjugate() * truth->second.b_N_T) * kTeslaToMicro;
        if (s.has_covariance()) {
          // Diagonal of the row-major 3x3 attitude-error covariance [rad^2].
          const auto& P = s.attitude_cov_body_rad2();
          r.sigma3_B_deg = Eigen::Vector3d(std::sqrt(std::max(P[0], 0.0)), std::sqrt(std::max(P[4], 0.0)),
                                           std::sqrt(std::max(P[8], 0.0))) *
                           3.0 * kRadToDeg;
          d.estimate_covariance = true;
        }
        d.estimate.push_back(r);
      });
  forEachSample<bus::topics::kDipoleCmd>(recording, [&](std::uint64_t, const msg::DipoleCmd& s) {
    d.dipole.push_back({seconds(s.header().sim_time_ns()), bus::vec3(s.m_body_Am2()), s.active()});
  });
  forEachSample<bus::topics::kThrusterCmd>(recording, [&](std::uint64_t, const msg::ThrusterCmd& s) {
    ThrusterRow r{seconds(s.header().sim_time_ns()), {}, 0.0, s.pulse(), s.braking(),
                  static_cast<int>(s.phase())};
    d.thruster_count = std::min<std::size_t>(s.thruster_count(), r.on_time_s.size());
    for (std::size_t i = 0; i < d.thruster_count; ++i) {
      r.on_time_s[i] = s.on_time_s()[i];
      r.total_on_time_s += r.on_time_s[i];
    }
    if (r.total_on_time_s > 0 || r.pulse != 0) d.thruster.push_back(r);
  });
  forEachSample<bus::topics::kFaultEvent>(recording, [&](std::uint64_t, const msg::FaultEvent& s) {
    std::string topic = bus::text(s.topic());
    if (topic.rfind("flatsat/", 0) == 0) topic.erase(0, 8);
    d.events.push_back({seconds(s.header().sim_time_ns()),
                        "fault " + bus::text(s.header().source()) + " " + bus::text(s.kind()) +
                            (topic.empty() ? "" : " " + topic) + (s.active() ? " on" : " off")});
  });
  forEachSample<bus::topics::kCommandAck>(recording, [&](std::uint64_t, const msg::CommandAck& s) {
    if (!s.accepted()) return;  // a refused command changed nothing
    d.events.push_back({seconds(s.header().sim_time_ns()), bus::text(s.command()) + " " + bus::text(s.reason())});
  });
  std::stable_sort(d.events.begin(), d.events.end(),
                   [](const EventRow& a, const EventRow& b) { return a.t_s < b.t_s; });
  return d;
}

}  // namespace flatsat::analysis
