// SPDX-License-Identifier: Apache-2.0
#include "components/estimator/AttitudeEstimator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "components/common/Validation.hpp"
#include "sim/Attitude.hpp"

namespace flatsat::estimator {

namespace {

/// [-] ceiling of k_P·Δt. With two orthogonal vectors ω_mes ≈ (2I − Σ v vᵀ)θ has gain up to
/// 2 on the attitude error θ, so k_P·Δt ≤ ½ keeps one step from overshooting; only reached
/// after a long gap between samples.
constexpr double kMaxCorrectionGain = 0.5;

/// Unit vector of v into `unit`; false for a zero or non-finite v.
bool normalizeInto(const Eigen::Vector3d& v, Eigen::Vector3d& unit) {
  const double n = v.norm();
  if (!(n > 0.0) || !std::isfinite(n)) {
    return false;
  }
  unit = v / n;
  return true;
}

}  // namespace

bool triad(const Eigen::Vector3d& v1_B, const Eigen::Vector3d& v2_B, const Eigen::Vector3d& v1_N,
           const Eigen::Vector3d& v2_N, Eigen::Quaterniond& q_NB) {
  Eigen::Vector3d r1_B;
  Eigen::Vector3d r1_N;
  Eigen::Vector3d u2_B;
  Eigen::Vector3d u2_N;
  if (!normalizeInto(v1_B, r1_B) || !normalizeInto(v1_N, r1_N) || !normalizeInto(v2_B, u2_B) ||
      !normalizeInto(v2_N, u2_N)) {
    return false;
  }
  const Eigen::Vector3d c_B = r1_B.cross(u2_B);
  const Eigen::Vector3d c_N = r1_N.cross(u2_N);
  if (!(c_B.norm() >= kMinTriadSine) || !(c_N.norm() >= kMinTriadSine)) {
    return false;
  }
  // Orthonormal triads {r1, r2 = r1×v2/|r1×v2|, r3 = r1×r2} in both frames; R_NB = M_N M_Bᵀ.
  Eigen::Matrix3d M_B;
  Eigen::Matrix3d M_N;
  M_B.col(0) = r1_B;
  M_B.col(1) = c_B.normalized();
  M_B.col(2) = r1_B.cross(M_B.col(1));
  M_N.col(0) = r1_N;
  M_N.col(1) = c_N.normalized();
  M_N.col(2) = r1_N.cross(M_N.col(1));
  q_NB = Eigen::Quaterniond(Eigen::Matrix3d(M_N * M_B.transpose())).normalized();
  return true;
}

std::vector<std::string> AttitudeEstimatorParams::validate() const {
  std::vector<std::string> errors;
  requireNonNegative(errors, "kp_per_s", kp_per_s);
  requireNonNegative(errors, "ki_per_s2", ki_per_s2);
  requirePositive(errors, "max_bias_rad_s", max_bias_rad_s);
  return errors;
}

AttitudeEstimator::AttitudeEstimator(const Params& params) : params_(params) {
  if (const auto errors = params_.validate(); !errors.empty()) {
    std::string message = "AttitudeEstimatorParams invalid:";
    for (const auto& e : errors) {
      message += " " + e + ";";
    }
    throw std::invalid_argument(message);
  }
}

void AttitudeEstimator::reset() {
  q_NB_.setIdentity();
  bias_B_rad_s_.setZero();
  initialized_ = false;
  has_last_t_ = false;
}

void AttitudeEstimator::restore(const State& state) {
  q_NB_ = state.q_NB;
  bias_B_rad_s_ = state.bias_B_rad_s;
  initialized_ = state.initialized;
  last_t_ns_ = state.last_t_ns;
  has_last_t_ = state.has_last_t;
}

AttitudeEstimatorOutput AttitudeEstimator::step(const Input& in, std::int64_t t_ns) {
  const double dt_s =
      has_last_t_ ? std::max(0.0, static_cast<double>(t_ns - last_t_ns_) * 1e-9) : 0.0;
  last_t_ns_ = t_ns;
  has_last_t_ = true;

  Eigen::Vector3d s_B;
  Eigen::Vector3d s_N;
  Eigen::Vector3d b_B;
  Eigen::Vector3d b_N;
  const bool sun_ok = in.sun_valid && normalizeInto(in.sun_B_meas_unit, s_B) &&
                      normalizeInto(in.sun_N_ref_unit, s_N);
  const bool field_ok =
      in.b_valid && normalizeInto(in.b_B_meas_T, b_B) && normalizeInto(in.b_N_ref_T, b_N);

  Output out;
  if (!initialized_) {
    // The Sun is the primary: the sun sensor is far more accurate than the field model.
    if (sun_ok && params_.sun_only_init) {
      q_NB_ = Eigen::Quaterniond::FromTwoVectors(s_B, s_N);
      initialized_ = out.sun_used = true;
    } else {
      initialized_ = sun_ok && field_ok && triad(s_B, b_B, s_N, b_N, q_NB_);
      out.sun_used = out.field_used = initialized_;
    }
  } else {
    // Mahony, Hamel & Pflimlin 2008, Eq. (32), in quaternion form:
    //   q̇ = ½ q ⊗ (ω_y − b̂ + k_P ω_mes),  ḃ = −k_I ω_mes,  ω_mes = Σ v_i × v̂_i,
    // with v_i measured and v̂_i = R(q)ᵀ v_ref,i predicted (weights k_i/2 = 1). Discretised as a
    // gyro prediction over Δt with the exact exponential, then the correction evaluated at the
    // predicted attitude, so measurement and state refer to the same instant.
    q_NB_ = q_NB_ * sim::quatFromRotationVector((in.w_gyro_B_rad_s - bias_B_rad_s_) * dt_s);
    const Eigen::Matrix3d R_BN = q_NB_.toRotationMatrix().transpose();
    Eigen::Vector3d w_mes = Eigen::Vector3d::Zero();
    if (sun_ok) {
      w_mes += s_B.cross(R_BN * s_N);
      out.sun_used = true;
    }
    if (field_ok && params_.use_magnetometer) {
      w_mes += b_B.cross(R_BN * b_N);
      out.field_used = true;
    }
    const double kp_dt = std::min(params_.kp_per_s * dt_s, kMaxCorrectionGain);
    q_NB_ = (q_NB_ * sim::quatFromRotationVector(kp_dt * w_mes)).normalized();
    const Eigen::Vector3d bias_unclamped = bias_B_rad_s_ - params_.ki_per_s2 * dt_s * w_mes;
    bias_B_rad_s_ = bias_unclamped.cwiseMax(-params_.max_bias_rad_s).cwiseMin(params_.max_bias_rad_s);
    out.bias_clamped = bias_unclamped != bias_B_rad_s_;
  }

  out.initialized = initialized_;
  out.q_NB = q_NB_;
  out.gyro_bias_B_rad_s = bias_B_rad_s_;
  out.w_NB_B_rad_s = in.w_gyro_B_rad_s - bias_B_rad_s_;
  if (initialized_ && normalizeInto(in.sun_N_ref_unit, s_N)) {
    out.sun_B_est_unit = q_NB_.conjugate() * s_N;
  }
  return out;
}

}  // namespace flatsat::estimator
