// SPDX-License-Identifier: Apache-2.0
#include "components/gyro/GyroModel.hpp"

#include <cmath>
#include <stdexcept>

#include "components/common/Validation.hpp"

namespace flatsat::gyro {

std::vector<std::string> GyroParams::validate() const {
  std::vector<std::string> errors;
  requireNonNegative(errors, "angle_random_walk_rad_per_sqrt_s", angle_random_walk_rad_per_sqrt_s);
  requireNonNegative(errors, "rate_random_walk_rad_per_s_sqrt_s", rate_random_walk_rad_per_s_sqrt_s);
  requireFinite(errors, "bias0_B_rad_s", bias0_B_rad_s);
  if (!(scale_factor.array().abs() < 0.1).all()) errors.push_back("scale_factor: each must be in (-0.1, 0.1)");
  if (!(misalignment_rad.array().abs() < 0.1).all()) {
    errors.push_back("misalignment_rad: each must be in (-0.1, 0.1)");
  }
  return errors;
}

namespace {

/// ω_sensed = (I + S)(I − [m×]) ω: each axis reads its rate scaled by 1 + s_i about an input
/// axis turned by the small rotation m (the scale-factor and input-axis-misalignment terms of
/// the IEEE Std 952-1997 gyro model equation, to first order in m).
Eigen::Matrix3d sensedFromTrue(const GyroParams& p) {
  Eigen::Matrix3d cross;
  const Eigen::Vector3d& m = p.misalignment_rad;
  cross << 0.0, -m.z(), m.y(), m.z(), 0.0, -m.x(), -m.y(), m.x(), 0.0;
  return (Eigen::Matrix3d::Identity() + p.scale_factor.asDiagonal().toDenseMatrix()) *
         (Eigen::Matrix3d::Identity() - cross);
}

}  // namespace

GyroModel::GyroModel(const Params& params)
    : params_(params), sensed_from_true_(sensedFromTrue(params)), noise_(params.seed),
      bias_B_rad_s_(params.bias0_B_rad_s) {
  if (const auto errors = params_.validate(); !errors.empty()) {
    std::string message = "GyroParams invalid:";
    for (const auto& e : errors) {
      message += " " + e + ";";
    }
    throw std::invalid_argument(message);
  }
}

void GyroModel::reset() {
  noise_.reset();
  bias_B_rad_s_ = params_.bias0_B_rad_s;
  has_last_t_ = false;
}

GyroOutput GyroModel::step(const Input& in, std::int64_t t_ns) {
  // Drawn on every call so that sample k always uses the same draws, whatever the intervals.
  const Eigen::Vector3d n_u = noise_.vector<3>(1.0);
  const Eigen::Vector3d n_v = noise_.vector<3>(1.0);
  const double dt_s = has_last_t_ ? static_cast<double>(t_ns - last_t_ns_) * 1e-9 : 0.0;
  last_t_ns_ = t_ns;
  has_last_t_ = true;

  Output out;
  const Eigen::Vector3d w_sensed = sensed_from_true_ * in.w_NB_B_rad_s;
  if (!(dt_s > 0.0)) {
    out.w_NB_B_rad_s = w_sensed + bias_B_rad_s_;
    out.bias_B_rad_s = bias_B_rad_s_;
    return out;
  }
  // Farrenkopf model ω_meas = ω + β + η_v, β̇ = η_u (Farrenkopf 1978, J. Guidance and Control
  // 1(4); σ_v, σ_u are the ARW and RRW coefficients N, K of IEEE Std 952-1997), discretised
  // exactly for the mean rate over Δt (Markley & Crassidis 2014, Fundamentals of Spacecraft
  // Attitude Determination and Control, p. 147):
  //   β_k = β_{k-1} + σ_u √Δt N_u
  //   ω̃_k = ω_k + ½(β_k + β_{k-1}) + √(σ_v²/Δt + σ_u² Δt/12) N_v
  // With σ_u = 0 the white part is the familiar ARW/√Δt.
  const double arw = params_.angle_random_walk_rad_per_sqrt_s;
  const double rrw = params_.rate_random_walk_rad_per_s_sqrt_s;
  const Eigen::Vector3d bias_prev = bias_B_rad_s_;
  bias_B_rad_s_ += rrw * std::sqrt(dt_s) * n_u;
  const double sigma_v = std::sqrt(arw * arw / dt_s + rrw * rrw * dt_s / 12.0);
  out.w_NB_B_rad_s = w_sensed + 0.5 * (bias_prev + bias_B_rad_s_) + sigma_v * n_v;
  out.bias_B_rad_s = bias_B_rad_s_;
  return out;
}

}  // namespace flatsat::gyro
