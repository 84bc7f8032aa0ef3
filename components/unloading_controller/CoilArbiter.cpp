// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/CoilArbiter.hpp"

#include <cmath>
#include <stdexcept>

namespace flatsat::unloading_controller {

namespace {
std::int64_t toNs(double s) { return static_cast<std::int64_t>(std::llround(s * 1e9)); }

bool windowValid(const CoilRequest& r) {
  return r.quiet_s >= 0.0 && r.pulse_s > 0.0 && r.quiet_after_s >= 0.0 && r.m_B_Am2.allFinite() &&
         std::isfinite(r.quiet_s + r.pulse_s + r.quiet_after_s) && r.law_pulse_min_Am2 >= 0.0 &&
         std::isfinite(r.law_pulse_min_Am2);
}
}  // namespace

CoilArbiter::CoilArbiter(const Eigen::Vector3d& max_dipole_Am2) : max_dipole_Am2_(max_dipole_Am2) {
  if (!(max_dipole_Am2.array() > 0.0).all() || !max_dipole_Am2.allFinite()) {
    throw std::invalid_argument("CoilArbiter: max_dipole_Am2: every coil must be finite and > 0");
  }
}

void CoilArbiter::reset() {
  window_ = {};
  last_served_ = 0;
  law_pulse_min_Am2_ = 0.0;
  pulse_started_ = false;
}

CoilArbiterOutput CoilArbiter::step(const std::optional<CoilRequest>& request,
                                    const Eigen::Vector3d& law_m_B_Am2, std::int64_t t_ns) {
  bool running = window_.phase == CoilPhase::kQuiet || window_.phase == CoilPhase::kPulse ||
                 window_.phase == CoilPhase::kQuietAfter;
  if (running && t_ns >= window_.t2_ns) {
    window_.phase = CoilPhase::kDone;
    running = false;
  }
  if (!running && request && request->id != 0 && request->id != last_served_) {
    last_served_ = request->id;
    window_ = {};
    window_.request_id = request->id;
    if (!windowValid(*request) ||
        (request->m_B_Am2.cwiseAbs().array() > max_dipole_Am2_.array()).any()) {
      window_.phase = CoilPhase::kRefused;
    } else {
      window_.phase = CoilPhase::kQuiet;
      window_.t0_ns = t_ns;
      window_.t1_ns = t_ns + toNs(request->quiet_s);
      window_.pulse_end_ns = window_.t1_ns + toNs(request->pulse_s);
      window_.t2_ns = window_.pulse_end_ns + toNs(request->quiet_after_s);
      window_.m_B_Am2 = request->m_B_Am2;
      law_pulse_min_Am2_ = request->law_pulse_min_Am2;
      pulse_started_ = false;
    }
  }
  CoilArbiterOutput out;
  switch (window_.phase) {
    case CoilPhase::kQuiet:
    case CoilPhase::kPulse:
    case CoilPhase::kQuietAfter:
      window_.phase = t_ns < window_.t1_ns          ? CoilPhase::kQuiet
                      : t_ns < window_.pulse_end_ns ? CoilPhase::kPulse
                                                    : CoilPhase::kQuietAfter;
      out.window_active = true;
      if (window_.phase == CoilPhase::kPulse && !pulse_started_) {
        pulse_started_ = true;
        const Eigen::Vector3d direction = window_.m_B_Am2.normalized();
        const double along = std::abs(law_m_B_Am2.dot(direction));
        if (law_pulse_min_Am2_ > 0.0 && along >= law_pulse_min_Am2_ && along >= 0.5 * law_m_B_Am2.norm() &&
            (law_m_B_Am2.cwiseAbs().array() <= max_dipole_Am2_.array()).all()) {
          window_.m_B_Am2 = law_m_B_Am2;
          window_.law_pulse = true;
        }
      }
      if (window_.phase == CoilPhase::kPulse) out.m_B_Am2 = window_.m_B_Am2;
      break;
    default:
      break;
  }
  if (!out.window_active) out.m_B_Am2 = law_m_B_Am2;
  out.report = window_;
  return out;
}

}  // namespace flatsat::unloading_controller
