// SPDX-License-Identifier: Apache-2.0
#include "analysis/MagneticMetrics.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/Conventions.hpp"

namespace flatsat::analysis {

void MagneticMetrics::add(double t_s, const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& w_B_rad_s,
                          const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s,
                          const Eigen::Vector3d& dipole_B_Am2) {
  const double rate = w_B_rad_s.norm();
  last_.rate_deg_s_final = rate * kRadToDeg;
  if (rate >= params_.detumbled_rate_rad_s) {
    last_.time_to_detumble_s.reset();
  } else if (!last_.time_to_detumble_s) {
    last_.time_to_detumble_s = t_s;
  }
  if (params_.spin_rate_rad_s != 0.0) {
    const Eigen::Vector3d normal_N = r_N_m.cross(v_N_m_s).normalized();
    const Eigen::Vector3d axis_N = q_NB * params_.spin_axis_B;
    const double axis_error = std::acos(std::clamp(axis_N.dot(normal_N), -1.0, 1.0));
    const double rate_error = std::abs((q_NB * w_B_rad_s).dot(normal_N) - params_.spin_rate_rad_s) /
                              std::abs(params_.spin_rate_rad_s);
    last_.spin_axis_error_deg = axis_error * kRadToDeg;
    last_.spin_rate_error_pct = 100.0 * rate_error;
    if (axis_error >= params_.axis_tolerance_rad || rate_error >= params_.rate_tolerance) {
      last_.time_to_capture_s.reset();
    } else if (!last_.time_to_capture_s) {
      last_.time_to_capture_s = t_s;
    }
  }
  duty_sum_ += (dipole_B_Am2.cwiseAbs().array() / params_.max_dipole_Am2.array()).mean();
  ++samples_;
}

MagneticMetricsResult MagneticMetrics::result() const {
  MagneticMetricsResult r = last_;
  r.coil_duty = samples_ > 0 ? duty_sum_ / static_cast<double>(samples_) : 0.0;
  return r;
}

}  // namespace flatsat::analysis
