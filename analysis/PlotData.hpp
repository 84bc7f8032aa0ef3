// SPDX-License-Identifier: Apache-2.0
#pragma once
// The time series `flatsat plot` draws, computed from a recording (and,
// when the run's scenario.yaml is at hand, the plant's limits and epoch).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/Time.hpp"

namespace flatsat::analysis {

/// What the scenario adds to the figures; every field optional.
struct PlotContext {
  Eigen::Vector3d pointing_axis_B = Eigen::Vector3d::UnitX();  ///< [-] controller's axis
  std::optional<sim::UtcEpoch> epoch;              ///< t = 0 (ground track from GMST)
  std::optional<double> acquisition_s;             ///< [s] metrics start
  std::optional<double> wheel_capacity_Nms;        ///< [N m s] smallest wheel's capacity
  std::optional<Eigen::Vector3d> max_dipole_Am2;   ///< [A m^2] per coil
};

/// Reads what the figures need from a run's scenario file; problems leave
/// fields unset (the figures then go without them).
PlotContext readPlotContext(const std::string& scenario_file);

/// One row per recorded truth sample.
struct TruthRow {
  double t_s;                        ///< [s] simulated time
  double pointing_error_deg;         ///< [deg] axis to Sun
  Eigen::Vector3d w_B_deg_s;         ///< [deg/s] body rate
  std::array<double, 4> wheel_rad_s; ///< [rad/s]
  double h_wheels_Nms;               ///< [N m s] |h| stored in the wheels
  Eigen::Vector3d b_B_uT;            ///< [µT] true field, body axes
  Eigen::Vector3d dipole_B_Am2;      ///< [A m^2] applied over the last step
  double illumination;               ///< [-]
  double lat_deg, lon_deg;           ///< [deg] sub-satellite point (PlotData::track says which)
};

struct MagnetometerRow {
  double t_s;
  Eigen::Vector3d b_B_uT;       ///< [µT] measured
  Eigen::Vector3d error_B_nT;   ///< [nT] measured − true (bias and noise)
};

struct EstimateRow {
  double t_s;
  double error_deg;             ///< [deg] rotation angle from truth to estimate
  Eigen::Vector3d error_B_deg;  ///< [deg] small-angle error per body axis
  Eigen::Vector3d b_B_uT;       ///< [µT] true inertial field seen through the estimated attitude
  /// [deg] 3σ of the attitude error per body axis, from the filter's
  /// covariance (has_covariance); unset for a method that publishes none.
  std::optional<Eigen::Vector3d> sigma3_B_deg;
};

/// A step at which some thruster fired.
struct ThrusterRow {
  double t_s;
  std::array<double, 12> on_time_s;  ///< [s] per thruster (ThrusterCmd.on_time_s)
  double total_on_time_s;  ///< [s] summed over the thrusters
  int pulse;         ///< [-] +1 / -1 about the controlled axis, 0 none
  bool braking;      ///< [-] a braking pulse (else a correction)
  int phase;         ///< [-] 0 acquiring, 1 correcting, 2 coasting, 3 braking, 4 holding
};

struct DipoleRow {
  double t_s;
  Eigen::Vector3d m_B_Am2;  ///< [A m^2] commanded
  bool active;
};

/// Something that happened at a moment of the run, marked on every time plot:
/// a fault beginning or ending (flatsat/fault_event), an operator command a
/// component accepted (flatsat/command_ack).
struct EventRow {
  double t_s;
  std::string label;  ///< short: "fault gyro bias on", "param kp_Nm_per_rad = 0.9"
};

struct PlotData {
  /// Where TruthRow's latitude comes from: the truth's own geodetic
  /// sub-satellite point, else the inertial position rotated by GMST
  /// (needs the scenario's epoch), else none.
  enum class Track { kNone, kGeodetic, kGeocentric };
  Track track = Track::kNone;
  std::size_t wheel_count = 0;
  std::vector<TruthRow> truth;
  std::vector<MagnetometerRow> magnetometer;
  std::vector<EstimateRow> estimate;
  std::vector<DipoleRow> dipole;
  std::vector<ThrusterRow> thruster;  ///< firing steps only: pulses are sparse
  std::size_t thruster_count = 0;
  bool estimate_covariance = false;  ///< some estimate carries its covariance
  std::vector<EventRow> events;      ///< in time order
};

PlotData readPlotData(const std::string& recording_path, const PlotContext& context);

}  // namespace flatsat::analysis
