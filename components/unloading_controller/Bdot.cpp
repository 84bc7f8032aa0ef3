// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/Bdot.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "components/common/Validation.hpp"

namespace flatsat::unloading_controller {

std::vector<std::string> BdotParams::validate() const {
  std::vector<std::string> errors;
  requirePositive(errors, "gain_Am2_s_per_T", gain_Am2_s_per_T);
  requireAllPositive(errors, "max_dipole_Am2", max_dipole_Am2, "coil");
  requireFinite(errors, "omega_ref_B_rad_s", omega_ref_B_rad_s);
  requireNonNegative(errors, "filter_time_constant_s", filter_time_constant_s);
  requireNonNegative(errors, "deadband_rad_s", deadband_rad_s);
  requirePositive(errors, "max_sample_gap_s", max_sample_gap_s);
  requirePositive(errors, "min_field_T", min_field_T);
  return errors;
}

Bdot::Bdot(const Params& params) : params_(validated(params, "BdotParams invalid")) {
}

namespace {

/// TRIAD (Black 1964; Shuster & Oh, "Three-axis attitude determination from vector
/// observations", JGC 4(1), 1981, eq. 3-6): the orthonormal triad of a primary and a
/// secondary direction.
Eigen::Matrix3d triad(const Eigen::Vector3d& primary, const Eigen::Vector3d& secondary) {
  Eigen::Matrix3d m;
  m.col(0) = primary.normalized();
  m.col(1) = m.col(0).cross(secondary).normalized();
  m.col(2) = m.col(0).cross(m.col(1));
  return m;
}

}  // namespace

void Bdot::reset() {
  previous_b_N_T_.reset();
  previous_b_B_T_.reset();
  b_dot_B_T_s_.reset();
}

BdotOutput Bdot::step(const Input& in, std::int64_t t_ns) {
  Output out;
  const double b_norm = in.b_B_T.norm();
  if (!in.b_valid || !std::isfinite(b_norm) || b_norm < params_.min_field_T) {
    return out;  // the previous sample stays: the next difference spans the gap
  }
  const double dt_s = static_cast<double>(t_ns - previous_t_ns_) * 1e-9;
  if (previous_b_B_T_ && (dt_s > params_.max_sample_gap_s || in.model.has_value() != previous_b_N_T_.has_value())) {
    reset();
  }
  if (previous_b_B_T_ && dt_s > 0.0) {
    Eigen::Vector3d raw = (in.b_B_T - *previous_b_B_T_) / dt_s;
    if (in.model) {
      // In body axes Ḃ = R ḃ_N − ω × B: the body's turn and the field's own. The model
      // gives ḃ_N (same secant, same midpoint); R̂ is the TRIAD of the known axis
      // (primary) and the field, exact once the body holds axis_B on axis_N. What is
      // left, B × ω, sees the body's rate alone: no orbit-rate approximation
      // (the seed's Q = B × ω0) and none of the field's uneven turn over the orbit.
      const Eigen::Vector3d b_dot_N_T_s = (in.model->b_N_T - *previous_b_N_T_) / dt_s;
      const Eigen::Vector3d b_mid_N_T = 0.5 * (in.model->b_N_T + *previous_b_N_T_);
      const Eigen::Vector3d b_mid_B_T = 0.5 * (in.b_B_T + *previous_b_B_T_);
      const Eigen::Matrix3d R_BN = triad(in.model->axis_B_unit, b_mid_B_T) *
                                   triad(in.model->axis_N_unit, b_mid_N_T).transpose();
      raw -= R_BN * b_dot_N_T_s;
    }
    // Backward-Euler first-order low-pass: stable for any Δt, unity gain at DC.
    const double alpha = dt_s / (params_.filter_time_constant_s + dt_s);
    b_dot_B_T_s_ = b_dot_B_T_s_ ? Eigen::Vector3d(*b_dot_B_T_s_ + alpha * (raw - *b_dot_B_T_s_)) : raw;
  }
  // The secant (B_k − B_{k−1})/Δt is the derivative at the interval's midpoint to
  // second order; the correction is taken there too. With B_k instead (the seed's
  // B_b) the two terms are half a step apart, an error |B| ω_ref² Δt/2 that at
  // 2 deg/s and 1 s is as large as the orbit-rate terms that align the spin axis.
  const Eigen::Vector3d b_mid_B_T = previous_b_B_T_ && dt_s > 0.0 ? Eigen::Vector3d(0.5 * (in.b_B_T + *previous_b_B_T_)) : in.b_B_T;
  if (!previous_b_B_T_ || dt_s > 0.0) {
    previous_b_B_T_ = in.b_B_T;
    previous_b_N_T_ = in.model ? std::optional<Eigen::Vector3d>(in.model->b_N_T) : std::nullopt;
    previous_t_ns_ = t_ns;
  }
  if (!b_dot_B_T_s_) return out;

  out.b_dot_B_T_s = *b_dot_B_T_s_;
  const Eigen::Vector3d& b_corrected_B_T = params_.correction_at_sample ? in.b_B_T : b_mid_B_T;
  out.p_B_T_s = out.b_dot_B_T_s - b_corrected_B_T.cross(params_.omega_ref_B_rad_s);
  out.rate_error_rad_s = out.p_B_T_s.norm() / b_norm;
  const double deadband_T_s = b_norm * params_.deadband_rad_s;
  const Eigen::Vector3d& m0 = params_.max_dipole_Am2;
  for (int i = 0; i < 3; ++i) {
    const double p = out.p_B_T_s[i];
    if (std::abs(p) < deadband_T_s || p == 0.0) continue;
    const double wanted = params_.shape == BdotShape::kBangBang ? -std::copysign(m0[i], p)
                                                                 : -params_.gain_Am2_s_per_T * p;
    out.m_B_Am2[i] = std::clamp(wanted, -m0[i], m0[i]);
    out.saturated = out.saturated || std::abs(wanted) >= m0[i];
  }
  out.active = true;
  return out;
}

}  // namespace flatsat::unloading_controller
