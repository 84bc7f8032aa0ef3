// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryFieldFromMomentum.hpp"

#include <cmath>

#include "bus/Convert.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "sim/Frames.hpp"
#include "sim/Time.hpp"

namespace flatsat::analysis {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

void FieldFromMomentumFigures::addTruth(std::uint64_t step, const TruthSample& t) {
  pairs_.addReference(step,
                      {bus::vec3(t.b_body_T()), bus::vec3(t.sun_inertial_unit()), bus::quat(t.q_inertial_body()),
                       t.header().sim_time_ns()},
                      [this](std::uint64_t, const TruthAt& truth, const FieldAt& field) { judge(truth, field); });
}

void FieldFromMomentumFigures::addField(std::uint64_t step, const FieldSample& f) {
  if (step >= last_step_) {
    last_step_ = step;
    cycles_ = f.cycles();
    failed_ = f.failed_cycles();
  }
  const double t_s = static_cast<double>(f.header().sim_time_ns()) * 1e-9;
  if (!f.valid() || t_s < acquisition_s_) return;
  pairs_.addSample(step, {bus::vec3(f.b_body_T()), f.roll_rad()},
                   [this](std::uint64_t, const TruthAt& truth, const FieldAt& field) { judge(truth, field); });
}

void FieldFromMomentumFigures::judge(const TruthAt& t, const FieldAt& f) {
  // The true roll: body y in the Sun-ecliptic frame, at the truth's own time.
  const double jd_tt = jd_epoch_ + (static_cast<double>(t.sim_time_ns) * 1e-9 + sim::kTtMinusUtc_s) / 86400.0;
  const Eigen::Matrix3d R_N_SE = sim::R_N_SunEcliptic(t.sun_N, jd_tt);
  const Eigen::Vector3d y_SE = R_N_SE.transpose() * (t.q_NB * Eigen::Vector3d::UnitY());
  const double field = (f.b_B_T - t.b_B_T).norm() / t.b_B_T.norm();
  const double roll = std::remainder(f.roll_rad - std::atan2(y_SE.z(), y_SE.y()), 2 * kPi);
  field2_ += field * field;
  roll2_ += roll * roll;
  ++n_;
}

void FieldFromMomentumFigures::summarize(nlohmann::ordered_json& summary) const {
  // Every estimator publishes the topic; a rig without S0 windows gets no S0 keys.
  if (cycles_ == 0 && failed_ == 0 && n_ == 0) return;
  summary["field_error_pct_rms"] = n_ ? 100.0 * std::sqrt(field2_ / n_) : NAN;
  summary["alpha_error_deg_rms"] = n_ ? std::sqrt(roll2_ / n_) * 180.0 / kPi : NAN;
  summary["s0_windows_solved"] = cycles_;
  summary["s0_windows_failed"] = failed_;
}

}  // namespace flatsat::analysis
