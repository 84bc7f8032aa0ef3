// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace flatsat::analysis {

/// The judges of detumbling and spin capture: thresholds and the
/// spin the controller was asked for.
struct MagneticMetricsParams {
  double detumbled_rate_rad_s = 0.2 * 3.14159265358979323846 / 180.0;  // [rad/s] |ω| below: detumbled
  double axis_tolerance_rad = 5.0 * 3.14159265358979323846 / 180.0;    // [rad] spin axis to orbit normal
  double rate_tolerance = 0.05;                                        // [-] |ω·n − ω_s| / ω_s
  Eigen::Vector3d spin_axis_B = Eigen::Vector3d::UnitZ();              // [-] unit, the chosen body axis
  double spin_rate_rad_s = 0.0;                                        // [rad/s] ω_s; 0: no spin judged
  Eigen::Vector3d max_dipole_Am2 = Eigen::Vector3d::Ones();            // [A m²] coil limits, > 0
};

struct MagneticMetricsResult {
  double rate_deg_s_final = 0.0;
  std::optional<double> time_to_detumble_s;  // from the start of the last stretch below the threshold
  double spin_axis_error_deg = 0.0;          // at the end
  double spin_rate_error_pct = 0.0;          // at the end
  std::optional<double> time_to_capture_s;   // from the start of the last stretch within both tolerances
  double coil_duty = 0.0;  // [-] mean over samples and coils of |m_i| / m0_i (1: every coil always at its limit)
};

/// Accumulates the true state sample by sample; a stretch that lasts to the
/// end of the run counts, one that a later excursion breaks does not.
class MagneticMetrics {
 public:
  explicit MagneticMetrics(const MagneticMetricsParams& params) : params_(params) {}

  /// t_s [s], attitude body → inertial, body rate [rad/s], position [m] and
  /// velocity [m/s] (inertial; their cross product is the orbit normal) and the
  /// applied dipole [A m²].
  void add(double t_s, const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& w_B_rad_s,
           const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s, const Eigen::Vector3d& dipole_B_Am2);

  MagneticMetricsResult result() const;

 private:
  MagneticMetricsParams params_;
  MagneticMetricsResult last_;
  double duty_sum_ = 0.0;
  std::size_t samples_ = 0;
};

}  // namespace flatsat::analysis
