// SPDX-License-Identifier: Apache-2.0
#include "components/estimator/Mekf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "components/common/Validation.hpp"
#include "components/estimator/AttitudeEstimator.hpp"
#include "sim/Attitude.hpp"

namespace flatsat::estimator {

namespace {

using Matrix3d = Eigen::Matrix3d;

/// [-] P(χ²_3 ≤ x) = erf(√(x/2)) − √(2x/π)·e^(−x/2) (Abramowitz & Stegun 26.4.5 for odd ν).
double chiSquare3Cdf(double x) {
  return std::erf(std::sqrt(0.5 * x)) - std::sqrt(2.0 * x / std::numbers::pi) * std::exp(-0.5 * x);
}

/// Any unit vector perpendicular to the unit vector u.
Eigen::Vector3d perpendicular(const Eigen::Vector3d& u) {
  const Eigen::Vector3d axis =
      std::abs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return u.cross(axis).normalized();
}

bool unitInto(const Eigen::Vector3d& v, Eigen::Vector3d& unit) {
  const double n = v.norm();
  if (!(n > 0.0) || !std::isfinite(n)) return false;
  unit = v / n;
  return true;
}

}  // namespace

double chiSquareQuantile(int dof, double probability) {
  if (dof == 2) return -2.0 * std::log1p(-probability);  // P(χ²_2 ≤ x) = 1 − e^(−x/2)
  if (dof != 3) throw std::invalid_argument("chiSquareQuantile: dof must be 2 or 3");
  double lo = 0.0, hi = 200.0;  // P(χ²_3 ≤ 200) = 1 − 1e-41
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (chiSquare3Cdf(mid) < probability ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<std::string> MekfParams::validate() const {
  std::vector<std::string> errors;
  requirePositive(errors, "gyro_arw_rad_per_sqrt_s", gyro_arw_rad_per_sqrt_s);
  requirePositive(errors, "gyro_rrw_rad_per_s_sqrt_s", gyro_rrw_rad_per_s_sqrt_s);
  requirePositive(errors, "sun_sigma_rad", sun_sigma_rad);
  requirePositive(errors, "magnetometer_noise_T", magnetometer_noise_T);
  requireNonNegative(errors, "field_model_sigma_rad", field_model_sigma_rad);
  requirePositive(errors, "magnetometer_bias_sigma_T", magnetometer_bias_sigma_T);
  requireNonNegative(errors, "magnetometer_bias_rw_T_per_sqrt_s", magnetometer_bias_rw_T_per_sqrt_s);
  requireAllPositive(errors, "star_tracker_sigma_B_rad", star_tracker_sigma_B_rad, "axis");
  requirePositive(errors, "initial_attitude_sigma_rad", initial_attitude_sigma_rad);
  requirePositive(errors, "initial_bias_sigma_rad_s", initial_bias_sigma_rad_s);
  require(errors, gate_probability > 0.0 && gate_probability < 1.0, "gate_probability",
          "must be in (0, 1)");
  requirePositive(errors, "max_attitude_sigma_rad", max_attitude_sigma_rad);
  require(errors, reacquire_after_rejections >= 1, "reacquire_after_rejections", "must be >= 1");
  return errors;
}

Mekf::Mekf(const Params& params) : params_(validated(params, "MekfParams invalid")) {
  gate2_ = chiSquareQuantile(2, params_.gate_probability);
  gate3_ = chiSquareQuantile(3, params_.gate_probability);
}

void Mekf::reset() {
  q_NB_.setIdentity();
  bias_B_rad_s_.setZero();
  mag_bias_B_T_.setZero();
  P_.setZero();
  initialized_ = false;
  rejected_total_ = 0;
  rejected_in_a_row_.fill(0);
  has_last_t_ = false;
}

void Mekf::restore(const State& state) {
  q_NB_ = state.q_NB;
  bias_B_rad_s_ = state.bias_B_rad_s;
  mag_bias_B_T_ = state.mag_bias_B_T;
  P_ = state.P;
  initialized_ = state.initialized;
  rejected_total_ = state.rejected_total;
  rejected_in_a_row_ = state.rejected_in_a_row;
  last_t_ns_ = state.last_t_ns;
  has_last_t_ = state.has_last_t;
}

void Mekf::propagate(const Eigen::Vector3d& w_gyro_B, double dt_s) {
  // Reference: q ← q ⊗ exp(ω̂Δt/2) with ω̂ = ω̃ − β̂, the exact solution for a rate held over Δt.
  const Eigen::Vector3d w = w_gyro_B - bias_B_rad_s_;
  q_NB_ = (q_NB_ * sim::quatFromRotationVector(w * dt_s)).normalized();

  // Error dynamics δθ̇ = −[ω̂×]δθ − Δβ − η_v, Δβ̇ = −η_u (Lefferts, Markley & Shuster 1982,
  // §IV), and their transition matrix in closed form for ω̂ held over Δt (Markley &
  // Crassidis 2014, §6.2.4; Crassidis & Junkins 2012, §7.2.1).
  const Matrix3d W = sim::skew(w);
  const Matrix3d W2 = W * W;
  const double n = w.norm();
  const double a = n * dt_s;
  double c1, c2, c3;  // sin(a)/n, (1 − cos a)/n², (a − sin a)/n³, as series when a is small
  if (a < 1e-4) {
    c1 = dt_s * (1.0 - a * a / 6.0);
    c2 = dt_s * dt_s * (0.5 - a * a / 24.0);
    c3 = dt_s * dt_s * dt_s * (1.0 / 6.0 - a * a / 120.0);
  } else {
    c1 = std::sin(a) / n;
    c2 = (1.0 - std::cos(a)) / (n * n);
    c3 = (a - std::sin(a)) / (n * n * n);
  }
  MekfMatrix Phi = MekfMatrix::Identity();
  Phi.block<3, 3>(0, 0) = Matrix3d::Identity() - W * c1 + W2 * c2;
  Phi.block<3, 3>(0, 3) = W * c2 - Matrix3d::Identity() * dt_s - W2 * c3;

  // Farrenkopf's discrete process noise (Farrenkopf 1978, J. Guidance and Control 1(4);
  // Markley & Crassidis 2014, §6.2.4; Crassidis & Junkins 2012, §7.2.1):
  //   Q = [(σ_v²Δt + σ_u²Δt³/3) I   −(σ_u²Δt²/2) I]
  //       [−(σ_u²Δt²/2) I            (σ_u²Δt) I    ]
  const double sv2 = params_.gyro_arw_rad_per_sqrt_s * params_.gyro_arw_rad_per_sqrt_s;
  const double su2 = params_.gyro_rrw_rad_per_s_sqrt_s * params_.gyro_rrw_rad_per_s_sqrt_s;
  // The magnetometer bias is a random walk of its own.
  const double sm2 = params_.magnetometer_bias_rw_T_per_sqrt_s * params_.magnetometer_bias_rw_T_per_sqrt_s;
  MekfMatrix Q = MekfMatrix::Zero();
  Q.block<3, 3>(0, 0).diagonal().setConstant(sv2 * dt_s + su2 * dt_s * dt_s * dt_s / 3.0);
  Q.block<3, 3>(0, 3).diagonal().setConstant(-0.5 * su2 * dt_s * dt_s);
  Q.block<3, 3>(3, 0).diagonal().setConstant(-0.5 * su2 * dt_s * dt_s);
  Q.block<3, 3>(3, 3).diagonal().setConstant(su2 * dt_s);
  Q.block<3, 3>(6, 6).diagonal().setConstant(sm2 * dt_s);

  P_ = Phi * P_ * Phi.transpose() + Q;
  P_ = 0.5 * (P_ + P_.transpose());
}

template <int M>
MeasurementUse Mekf::update(const Eigen::Matrix<double, M, 1>& innovation,
                            const Eigen::Matrix<double, M, kMekfStates>& H,
                            const Eigen::Matrix<double, M, M>& R, double gate) {
  using MatrixM = Eigen::Matrix<double, M, M>;
  const MatrixM S = H * P_ * H.transpose() + R;
  const Eigen::LDLT<MatrixM> S_ldlt(S);
  // Normalised innovation squared ν ᵀS⁻¹ν ~ χ²_M for a consistent filter (Bar-Shalom, Li &
  // Kirubarajan 2001, Estimation with Applications to Tracking and Navigation, §5.4.2): a
  // larger value is an outlier, not information.
  const double nis = innovation.dot(S_ldlt.solve(innovation));
  if (!(nis <= gate)) {
    ++rejected_total_;
    return MeasurementUse::kRejected;
  }
  const Eigen::Matrix<double, kMekfStates, M> K = S_ldlt.solve(H * P_).transpose();
  const MekfVector dx = K * innovation;
  // Joseph form keeps P symmetric positive definite under rounding (Bucy & Joseph 1968).
  const MekfMatrix I_KH = MekfMatrix::Identity() - K * H;
  P_ = I_KH * P_ * I_KH.transpose() + K * R * K.transpose();
  P_ = 0.5 * (P_ + P_.transpose());
  // Multiplicative reset: the error moves into the reference and restarts at zero
  // (Markley & Crassidis 2014, §6.2.3; Lefferts, Markley & Shuster 1982, §IV).
  q_NB_ = (q_NB_ * sim::quatFromRotationVector(dx.head<3>())).normalized();
  bias_B_rad_s_ += dx.segment<3>(3);
  mag_bias_B_T_ += dx.tail<3>();
  return MeasurementUse::kUsed;
}

MeasurementUse Mekf::directionUpdate(const Eigen::Vector3d& meas_B, const Eigen::Vector3d& ref_N,
                                     double sigma_rad, double field_scale) {
  Eigen::Vector3d m_B;
  Eigen::Vector3d r_N;
  if (!unitInto(meas_B, m_B) || !unitInto(ref_N, r_N)) return MeasurementUse::kAbsent;
  // Predicted b̂ = R(q)ᵀ r; the truth is b̂ + b̂ × δθ to first order. The measurement is the
  // measured unit vector's components along two axes e1, e2 ⊥ b̂ (predicted zero), which
  // removes the singular direction of the 3-vector model σ²(I − b bᵀ) (Shuster 1989, J.
  // Astronautical Sciences 37(1), "QUEST measurement model"): H_i = [(e_i × b̂)ᵀ 0 e_iᵀ/|B|],
  // the last block for the field, whose bias Δb_m moves the measured direction by
  // (I − b̂b̂ᵀ)Δb_m/|B|.
  const Eigen::Vector3d b_hat = q_NB_.conjugate() * r_N;
  if (m_B.dot(b_hat) <= 0.0) {
    ++rejected_total_;
    return MeasurementUse::kRejected;
  }
  const Eigen::Vector3d e1 = perpendicular(b_hat);
  const Eigen::Vector3d e2 = b_hat.cross(e1);
  Eigen::Matrix<double, 2, kMekfStates> H = Eigen::Matrix<double, 2, kMekfStates>::Zero();
  H.block<1, 3>(0, 0) = e1.cross(b_hat).transpose();
  H.block<1, 3>(1, 0) = e2.cross(b_hat).transpose();
  H.block<1, 3>(0, 6) = field_scale * e1.transpose();
  H.block<1, 3>(1, 6) = field_scale * e2.transpose();
  const Eigen::Vector2d innovation(e1.dot(m_B), e2.dot(m_B));
  const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * sigma_rad * sigma_rad;
  return update<2>(innovation, H, R, gate2_);
}

MeasurementUse Mekf::starUpdate(const Eigen::Quaterniond& q_NB_star) {
  // δq = q⁻¹ ⊗ q_star is the measured error rotation; 2·vec(δq) ≈ δθ with H = [I 0]
  // (Markley & Crassidis 2014, §6.2.5, attitude measurement).
  Eigen::Quaterniond dq = q_NB_.conjugate() * q_NB_star.normalized();
  if (dq.w() < 0.0) dq.coeffs() *= -1.0;
  const Eigen::Vector3d innovation = 2.0 * dq.vec();
  Eigen::Matrix<double, 3, kMekfStates> H = Eigen::Matrix<double, 3, kMekfStates>::Zero();
  H.leftCols<3>().setIdentity();
  const Eigen::Matrix3d R = params_.star_tracker_sigma_B_rad.cwiseAbs2().asDiagonal();
  return update<3>(innovation, H, R, gate3_);
}

bool Mekf::initialize(const Input& in) {
  if (in.star_valid && in.q_NB_star.coeffs().allFinite() && in.q_NB_star.norm() > 0.0) {
    q_NB_ = in.q_NB_star.normalized();
    P_.topLeftCorner<3, 3>() = params_.star_tracker_sigma_B_rad.cwiseAbs2().asDiagonal();
  } else if (in.sun_valid && in.b_valid &&
             triad(in.sun_B_meas_unit, in.b_B_meas_T - mag_bias_B_T_, in.sun_N_ref_unit,
                   in.b_N_ref_T, q_NB_)) {
    P_.topLeftCorner<3, 3>() = Matrix3d::Identity() * params_.initial_attitude_sigma_rad *
                               params_.initial_attitude_sigma_rad;
  } else {
    return false;
  }
  P_.rightCols<6>().setZero();
  P_.bottomRows<6>().setZero();
  P_.block<3, 3>(3, 3) = Matrix3d::Identity() * params_.initial_bias_sigma_rad_s *
                         params_.initial_bias_sigma_rad_s;
  P_.block<3, 3>(6, 6) = Matrix3d::Identity() * params_.magnetometer_bias_sigma_T *
                         params_.magnetometer_bias_sigma_T;
  rejected_in_a_row_.fill(0);
  return true;
}

void Mekf::countRejections(const Output& out) {
  const MeasurementUse uses[] = {out.sun, out.field, out.star};
  for (std::size_t i = 0; i < rejected_in_a_row_.size(); ++i) {
    if (uses[i] == MeasurementUse::kRejected) ++rejected_in_a_row_[i];
    if (uses[i] == MeasurementUse::kUsed) rejected_in_a_row_[i] = 0;
  }
}

MekfOutput Mekf::step(const Input& in, std::int64_t t_ns) {
  const double dt_s =
      has_last_t_ ? std::max(0.0, static_cast<double>(t_ns - last_t_ns_) * 1e-9) : 0.0;
  last_t_ns_ = t_ns;
  has_last_t_ = true;

  Output out;
  if (*std::max_element(rejected_in_a_row_.begin(), rejected_in_a_row_.end()) >=
      params_.reacquire_after_rejections) {
    // A sensor has disagreed with the estimate for a long while: more likely the estimate,
    // pulled off by the others, is wrong than the sensor. Start over from the vectors.
    initialized_ = false;
  }
  if (!initialized_) {
    initialized_ = initialize(in);
    if (initialized_) {
      out.star = in.star_valid ? MeasurementUse::kUsed : MeasurementUse::kAbsent;
      if (!in.star_valid) out.sun = out.field = MeasurementUse::kUsed;
    }
  } else {
    if (dt_s > 0.0) propagate(in.w_gyro_B_rad_s, dt_s);
    // Sequential scalar-block updates with a reset after each: equivalent to one batch update
    // for uncorrelated measurements, and each gate sees the others' corrections.
    if (in.star_valid) out.star = starUpdate(in.q_NB_star);
    if (in.sun_valid) {
      out.sun = directionUpdate(in.sun_B_meas_unit, in.sun_N_ref_unit, params_.sun_sigma_rad, 0.0);
    }
    if (in.b_valid) {
      // White noise σ_B per axis turns the direction by σ_B/|B| per transverse axis; the onboard
      // model's direction error adds in quadrature.
      const double field_scale = 1.0 / in.b_N_ref_T.norm();
      const double noise_rad = params_.magnetometer_noise_T * field_scale;
      const double sigma_rad = std::hypot(noise_rad, params_.field_model_sigma_rad);
      out.field = directionUpdate(in.b_B_meas_T - mag_bias_B_T_, in.b_N_ref_T, sigma_rad, field_scale);
    }
    countRejections(out);
  }

  out.initialized = initialized_;
  out.q_NB = q_NB_;
  out.gyro_bias_B_rad_s = bias_B_rad_s_;
  out.magnetometer_bias_B_T = mag_bias_B_T_;
  out.w_NB_B_rad_s = in.w_gyro_B_rad_s - bias_B_rad_s_;
  out.covariance = P_;
  out.rejected_total = rejected_total_;
  const double max_var = P_.topLeftCorner<3, 3>().diagonal().maxCoeff();
  out.valid = initialized_ && q_NB_.coeffs().allFinite() && P_.allFinite() &&
              max_var <= params_.max_attitude_sigma_rad * params_.max_attitude_sigma_rad;
  Eigen::Vector3d s_N;
  if (initialized_ && unitInto(in.sun_N_ref_unit, s_N)) out.sun_B_est_unit = q_NB_.conjugate() * s_N;
  return out;
}

}  // namespace flatsat::estimator
