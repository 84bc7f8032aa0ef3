// SPDX-License-Identifier: Apache-2.0
#include "components/estimator/FieldFromMomentumEstimator.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "components/common/Validation.hpp"

namespace flatsat::estimator {

std::vector<std::string> FieldFromMomentumParams::validate() const {
  std::vector<std::string> e;
  append(e, wheels.validate("wheels"));
  requirePositive(e, "quiet_s", quiet_s);
  requirePositive(e, "pulse_s", pulse_s);
  requireNonNegative(e, "settle_s", settle_s);
  requireNonNegative(e, "quiet_after_s", quiet_after_s);
  require(e, body_inertia_kg_m2.allFinite() &&
                 body_inertia_kg_m2.isApprox(body_inertia_kg_m2.transpose(), 1e-12),
          "body_inertia_kg_m2", "must be finite and symmetric");
  requirePositive(e, "dipole_Am2", dipole_Am2);
  require(e, cycle_period_s >= quiet_s + pulse_s + settle_s + quiet_after_s &&
                 std::isfinite(cycle_period_s),
          "cycle_period_s", "must be finite and >= quiet_s + pulse_s + settle_s + quiet_after_s");
  requirePositive(e, "max_sun_offset_rad", max_sun_offset_rad);
  requireNonNegative(e, "law_pulse_min_Am2", law_pulse_min_Am2);
  require(e, isNonNegative(average_s) && average_s <= quiet_s / 2, "average_s",
          "must be finite, >= 0 and <= quiet_s / 2");
  return e;
}

namespace {
constexpr std::int64_t toNs(double s) { return static_cast<std::int64_t>(std::llround(s * 1e9)); }
}  // namespace

double s0RollAngle(double by_T, double bz_T, double BY_T, double BZ_T) {
  const double reference2 = BY_T * BY_T + BZ_T * BZ_T;
  if (reference2 <= 0.0 || (by_T == 0.0 && bz_T == 0.0)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return std::atan2(by_T * BZ_T - bz_T * BY_T, by_T * BY_T + bz_T * BZ_T);
}

Eigen::Vector3d s0BodyField(const Eigen::Vector3d& b_SE_T, double alpha_rad) {
  const double c = std::cos(alpha_rad), s = std::sin(alpha_rad);
  return {b_SE_T.x(), c * b_SE_T.y() + s * b_SE_T.z(), -s * b_SE_T.y() + c * b_SE_T.z()};
}

FieldFromMomentumEstimator::FieldFromMomentumEstimator(const Params& params)
    : params_(validated(params, "FieldFromMomentumParams")), field_(params.average_s) {
  reset();
}

void FieldFromMomentumEstimator::reset() {
  field_.reset();
  references_.clear();
  pending_.reset();
  next_id_ = 1;
  next_request_ns_ = 0;
  valid_ = false;
  alpha_rad_ = 0.0;
  has_last_ = false;
  last_w_B_rad_s_.setZero();
  h_wheels_B_Nms_.setZero();
  cycles_ = failed_ = 0;
  sign_ = 1.0;
}

double FieldFromMomentumEstimator::keepSeconds() const {
  // A window starts at most one cycle after it was asked for (the owner may be
  // busy); keep the quiet interval's averaging span too.
  return params_.cycle_period_s + params_.quiet_s + params_.pulse_s + params_.settle_s +
         params_.quiet_after_s +
         params_.average_s + 1.0;
}

const FieldFromMomentumEstimator::Reference* FieldFromMomentumEstimator::referenceAt(std::int64_t t_ns) const {
  const Reference* best = nullptr;
  for (const auto& r : references_) {
    if (best == nullptr || std::llabs(r.t_ns - t_ns) < std::llabs(best->t_ns - t_ns)) best = &r;
  }
  return best;
}

void FieldFromMomentumEstimator::solve(const DipoleWindow& window, Output& out) {
  const auto solution = field_.solve(window, params_.settle_s);
  const Reference* reference = solution ? referenceAt(solution->t_ref_ns) : nullptr;
  if (!solution || reference == nullptr) {
    ++failed_;
    return;
  }
  // The field along the dipole is not observed; body x is on the Sun, so its
  // x component is the reference BX (seed S0), which fixes the part along m.
  const Eigen::Vector3d& m = solution->m_unit_B;
  if (std::abs(m.x()) < 0.5) {
    ++failed_;
    return;
  }
  const double along = (reference->b_SE_T.x() - solution->b_perp_B_T.x()) / m.x();
  const Eigen::Vector3d b_B = solution->b_perp_B_T + along * m;
  const double alpha = s0RollAngle(b_B.y(), b_B.z(), reference->b_SE_T.y(), reference->b_SE_T.z());
  if (!std::isfinite(alpha)) {
    ++failed_;
    return;
  }
  // Carry α from the pulse's mid-time to now with the gyro samples since.
  alpha_rad_ = alpha + field_.angleSince(solution->t_ref_ns, Eigen::Vector3d::UnitX());
  valid_ = true;
  ++cycles_;
  out.solved_now = true;
  out.b_cycle_B_T = b_B;
  out.t_cycle_ns = solution->t_ref_ns;
  out.along_dipole_Nm = solution->along_dipole_Nm;
}

FieldFromMomentumOutput FieldFromMomentumEstimator::step(const Input& in, std::int64_t t_ns) {
  Output out;
  const Eigen::Vector3d w = in.gyro_valid ? in.w_B_rad_s : last_w_B_rad_s_;
  if (in.gyro_valid) last_w_B_rad_s_ = in.w_B_rad_s;
  // The gyro sample is the mean rate since the previous one (GyroModel).
  if (has_last_ && valid_) alpha_rad_ += w.x() * static_cast<double>(t_ns - last_t_ns_) * 1e-9;
  last_t_ns_ = t_ns;
  has_last_ = true;

  if (in.tach_valid) {
    h_wheels_B_Nms_ = params_.wheels.momentum_B_Nms(in.wheel_speed_rad_s);
    const Eigen::Vector3d h = h_wheels_B_Nms_ + params_.body_inertia_kg_m2 * w;
    field_.add({t_ns, h, w}, keepSeconds());
  }
  references_.push_back({t_ns, in.R_SE_N * in.b_N_ref_T});
  while (!references_.empty() &&
         references_.front().t_ns < t_ns - toNs(keepSeconds())) {
    references_.pop_front();
  }

  if (pending_ && in.completed && in.completed->first == pending_->id) {
    solve(in.completed->second, out);
    pending_.reset();
  } else if (pending_ && in.refused && *in.refused == pending_->id) {
    ++failed_;
    pending_.reset();
  }
  const bool sun_on_x = in.sun_valid && in.sun_B_unit.norm() > 0.0 &&
                        in.sun_B_unit.normalized().x() >= std::cos(params_.max_sun_offset_rad);
  if (!pending_ && t_ns >= next_request_ns_ && sun_on_x) {
    WindowRequest r;
    r.id = next_id_++;
    if (params_.unloading_sign && valid_ && !references_.empty()) {
      // Cross-product law (Singer 1964): M ∝ H × B, so M × B = −k H⊥.
      const double x = h_wheels_B_Nms_.cross(s0BodyField(references_.back().b_SE_T, alpha_rad_)).x();
      if (x != 0.0) sign_ = x > 0.0 ? 1.0 : -1.0;
    }
    r.m_B_Am2 = Eigen::Vector3d::UnitX() * (sign_ * params_.dipole_Am2);
    r.quiet_s = params_.quiet_s;
    r.pulse_s = params_.pulse_s;
    r.quiet_after_s = params_.settle_s + params_.quiet_after_s;
    r.law_pulse_min_Am2 = params_.law_pulse_min_Am2;
    if (params_.alternate_sign && !(params_.unloading_sign && valid_)) sign_ = -sign_;
    pending_ = r;
    next_request_ns_ = t_ns + toNs(params_.cycle_period_s);
  }

  out.request = pending_;
  out.valid = valid_;
  out.alpha_rad = alpha_rad_;
  if (valid_ && !references_.empty()) out.b_B_T = s0BodyField(references_.back().b_SE_T, alpha_rad_);
  out.cycles = cycles_;
  out.failed_cycles = failed_;
  return out;
}

}  // namespace flatsat::estimator
