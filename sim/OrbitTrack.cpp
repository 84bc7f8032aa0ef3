// SPDX-License-Identifier: Apache-2.0
#include "sim/OrbitTrack.hpp"

#include <cmath>
#include <stdexcept>

#include "sim/Format.hpp"

namespace flatsat::sim {
namespace {

constexpr double kMaxStep_s = 600.0;

const OrbitTrackParams& checked(const OrbitTrackParams& params, const OrbitElements& elements) {
  std::vector<std::string> errors = params.validate();
  for (const std::string& error : elements.validate()) errors.push_back("elements." + error);
  if (!errors.empty()) {
    std::string message = "invalid OrbitTrack set-up: " + errors.front();
    for (std::size_t i = 1; i < errors.size(); ++i) message += "; " + errors[i];
    throw std::invalid_argument(message);
  }
  return params;
}

// Cubic Hermite interpolant through (t0, r0, v0) and (t1, r1, v1) at s = (t − t0)/h:
// r = r0 + h01 (r1 − r0) + h (h10 v0 + h11 v1) with h01 = 3s² − 2s³, h10 = s³ − 2s² + s,
// h11 = s³ − s² (h00 = 1 − h01), and v = dr/dt. Exact at both ends.
KeplerOrbit::State hermite(double t0_s, const KeplerOrbit::State& a, double t1_s, const KeplerOrbit::State& b,
                           double t_s) {
  const double h = t1_s - t0_s;
  const double s = (t_s - t0_s) / h;
  const double s2 = s * s;
  const double s3 = s2 * s;
  const Eigen::Vector3d chord = b.r_N_m - a.r_N_m;
  return KeplerOrbit::State{
      a.r_N_m + (3.0 * s2 - 2.0 * s3) * chord + h * ((s3 - 2.0 * s2 + s) * a.v_N_m_s + (s3 - s2) * b.v_N_m_s),
      (6.0 * (s - s2) / h) * chord + (3.0 * s2 - 4.0 * s + 1.0) * a.v_N_m_s + (3.0 * s2 - 2.0 * s) * b.v_N_m_s};
}

}  // namespace

std::vector<std::string> OrbitTrackParams::validate() const {
  std::vector<std::string> errors;
  if (propagator != OrbitPropagation::kNumerical) return errors;
  if (!(std::isfinite(step_s) && step_s > 0.0 && step_s <= kMaxStep_s)) {
    errors.push_back("step_s: " + formatNumber(step_s) + " s must be in (0, " + formatNumber(kMaxStep_s) + "]");
  }
  for (const std::string& error : forces.validate()) errors.push_back("forces." + error);
  return errors;
}

OrbitTrack::OrbitTrack(const OrbitTrackParams& params, const OrbitElements& elements, const UtcEpoch& epoch)
    : params_(checked(params, elements)), kepler_(elements) {
  if (params_.propagator == OrbitPropagation::kNumerical) propagator_.emplace(params_.forces, epoch, kepler_.at(0.0));
  reset();
}

void OrbitTrack::reset() {
  end_index_ = 0;
  end_ = Node{0.0, kepler_.at(0.0)};
  if (!propagator_) return;
  propagator_->restart(0.0, end_.state);
  advance();
}

void OrbitTrack::advance() {
  start_ = end_;
  ++end_index_;
  const double t_end_s = static_cast<double>(end_index_) * params_.step_s;
  propagator_->step(t_end_s - propagator_->time_s());
  end_ = Node{t_end_s, propagator_->state()};
}

OrbitTrack::State OrbitTrack::at(double t_s) {
  if (!propagator_) return kepler_.at(t_s);
  if (!std::isfinite(t_s)) return end_.state;
  while (t_s > end_.t_s) advance();
  return hermite(start_.t_s, start_.state, end_.t_s, end_.state, t_s);
}

void OrbitTrack::kick(double t_s, const Eigen::Vector3d& dr_N_m, const Eigen::Vector3d& dv_N_m_s) {
  if (!propagator_ || !std::isfinite(t_s) || !dr_N_m.allFinite() || !dv_N_m_s.allFinite()) return;
  while (t_s > end_.t_s) advance();
  // Integrated, not interpolated: the interpolant's velocity error would stay in
  // the orbit at every kick.
  propagator_->restart(start_.t_s, start_.state);
  propagator_->step(t_s - start_.t_s);
  State kicked = propagator_->state();
  kicked.r_N_m += dr_N_m;
  kicked.v_N_m_s += dv_N_m_s;
  start_ = Node{t_s, kicked};
  // A kick on a grid point starts the next interval there.
  if (end_.t_s <= t_s) ++end_index_;
  const double t_end_s = static_cast<double>(end_index_) * params_.step_s;
  propagator_->restart(t_s, kicked);
  propagator_->step(t_end_s - t_s);
  end_ = Node{t_end_s, propagator_->state()};
}

}  // namespace flatsat::sim
