// SPDX-License-Identifier: Apache-2.0
#include "components/estimator/FieldFromMomentum.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace flatsat::estimator {

namespace {
double seconds(std::int64_t t_ns) { return static_cast<double>(t_ns) * 1e-9; }
}  // namespace

FieldFromMomentum::FieldFromMomentum(double average_s) : average_s_(average_s) {
  if (!(average_s >= 0.0) || !std::isfinite(average_s)) {
    throw std::invalid_argument("FieldFromMomentum: average_s: must be finite and >= 0");
  }
}

void FieldFromMomentum::add(const MomentumSample& sample, double keep_s) {
  samples_.push_back(sample);
  const double oldest_s = seconds(sample.t_ns) - keep_s;
  while (!samples_.empty() && seconds(samples_.front().t_ns) < oldest_s) samples_.pop_front();
}

std::optional<FieldFromMomentum::Point> FieldFromMomentum::meanOver(std::int64_t from_ns,
                                                                        std::int64_t to_ns) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double t_sum = 0.0;
  int count = 0;
  for (const auto& s : samples_) {
    if (s.t_ns < from_ns || s.t_ns > to_ns) continue;
    sum += s.h_B_Nms;
    t_sum += seconds(s.t_ns);
    ++count;
  }
  if (count == 0) return std::nullopt;
  return Point{t_sum / count, sum / count};
}

Eigen::Vector3d FieldFromMomentum::rotationIntegral(double from_s, double to_s) const {
  Eigen::Vector3d integral = Eigen::Vector3d::Zero();
  const MomentumSample* previous = nullptr;
  for (const auto& s : samples_) {
    const double t = seconds(s.t_ns);
    if (t < from_s - 1e-9 || t > to_s + 1e-9) continue;
    if (previous != nullptr) {
      const double dt = t - seconds(previous->t_ns);
      integral += 0.5 * dt * (s.w_B_rad_s.cross(s.h_B_Nms) +
                              previous->w_B_rad_s.cross(previous->h_B_Nms));
    }
    previous = &s;
  }
  return integral;
}

double FieldFromMomentum::angleSince(std::int64_t t_ns, const Eigen::Vector3d& axis) const {
  double angle = 0.0;
  const MomentumSample* previous = nullptr;
  for (const auto& s : samples_) {
    if (previous != nullptr && s.t_ns > t_ns) {
      // The part of the first interval after t_ns only.
      const std::int64_t from = std::max(previous->t_ns, t_ns);
      angle += s.w_B_rad_s.dot(axis) * seconds(s.t_ns - from);
    }
    previous = &s;
  }
  return angle;
}

std::optional<FieldSolution> FieldFromMomentum::solve(const DipoleWindow& w, double settle_s) const {
  const double pulse_s = seconds(w.pulse_end_ns - w.t1_ns);
  const double m2 = w.m_B_Am2.squaredNorm();
  if (!(w.t0_ns < w.t1_ns && w.t1_ns < w.pulse_end_ns && w.pulse_end_ns <= w.t2_ns) || m2 <= 0.0) {
    return std::nullopt;
  }
  if (samples_.empty() || samples_.front().t_ns > w.t0_ns || samples_.back().t_ns < w.t2_ns) {
    return std::nullopt;  // the window is no longer (or not yet) in the buffer
  }
  // Each mean lies in a quiet stretch next to its instant, so every interval holds
  // whole pulses or none; the intervals run between the means' centroids.
  const auto a = static_cast<std::int64_t>(std::llround(average_s_ * 1e9));
  const std::int64_t p_end = std::min(w.t2_ns, w.pulse_end_ns + static_cast<std::int64_t>(
                                                                    std::llround(settle_s * 1e9)));
  const bool after = w.t2_ns - p_end >= 2 * a && w.t2_ns > p_end;
  const auto p0 = meanOver(w.t0_ns, w.t0_ns + a);
  const auto p1 = meanOver(w.t1_ns - a, w.t1_ns);
  const auto p2 = after ? meanOver(p_end, p_end + a) : meanOver(p_end, p_end);
  const auto p3 = after ? meanOver(w.t2_ns - a, w.t2_ns) : p2;
  if (!p0 || !p1 || !p2 || !p3) return std::nullopt;
  const double tau_a = p1->t_s - p0->t_s, tau_p = p2->t_s - p1->t_s, tau_c = p3->t_s - p2->t_s;
  if (!(tau_a > 0.0 && tau_p > 0.0)) return std::nullopt;

  const auto impulse = [&](const Point& a, const Point& b) {
    return Eigen::Vector3d(b.h_B_Nms - a.h_B_Nms + rotationIntegral(a.t_s, b.t_s));
  };
  const Eigen::Vector3d d_a = impulse(*p0, *p1) / tau_a;
  Eigen::Vector3d d_p = d_a;
  if (tau_c > 0.0) {
    const Eigen::Vector3d d_c = impulse(*p2, *p3) / tau_c;
    const double mid_a = 0.5 * (p0->t_s + p1->t_s), mid_p = 0.5 * (p1->t_s + p2->t_s),
                 mid_c = 0.5 * (p2->t_s + p3->t_s);
    d_p = d_a + (d_c - d_a) * (mid_p - mid_a) / (mid_c - mid_a);
  }
  const Eigen::Vector3d delta = impulse(*p1, *p2) - d_p * tau_p;  // = (m τ) × B

  FieldSolution out;
  out.m_unit_B = w.m_B_Am2 / std::sqrt(m2);
  out.b_perp_B_T = delta.cross(w.m_B_Am2) / (m2 * pulse_s);
  out.t_ref_ns = w.t1_ns + (w.pulse_end_ns - w.t1_ns) / 2;
  out.disturbance_B_Nm = d_p;
  out.along_dipole_Nm = delta.dot(out.m_unit_B) / pulse_s;
  return out;
}

}  // namespace flatsat::estimator
