// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryFieldFromMomentum.hpp"

#include <cmath>
#include <unordered_map>

#include "bus/Convert.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "sim/Frames.hpp"
#include "sim/Time.hpp"

namespace flatsat::analysis {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

FieldFromMomentumFigures::FieldFromMomentumFigures(const bus::Scenario& scenario, double jd_epoch,
                                                   const bus::Recording& recording)
    : scenario_(scenario),
      recorded_(recording.count(std::string(bus::topics::kFieldEstimate.name)) > 0),
      jd_epoch_(jd_epoch) {}

void FieldFromMomentumFigures::addTruth(std::uint64_t step, const TruthSample& t) {
  if (!recorded_) return;
  const double jd_tt = jd_epoch_ + (static_cast<double>(t.header().sim_time_ns()) * 1e-9 + sim::kTtMinusUtc_s) / 86400.0;
  const Eigen::Matrix3d R_N_SE = sim::R_N_SunEcliptic(bus::vec3(t.sun_inertial_unit()), jd_tt);
  const Eigen::Vector3d y_SE = R_N_SE.transpose() * (bus::quat(t.q_inertial_body()) * Eigen::Vector3d::UnitY());
  truth_[step] = {bus::vec3(t.b_body_T()), std::atan2(y_SE.z(), y_SE.y())};
}

void FieldFromMomentumFigures::summarize(const bus::Recording& recording, nlohmann::ordered_json& summary) const {
  if (!recorded_) return;
  using FieldDef = std::remove_cvref_t<decltype(bus::topics::kFieldEstimate)>;
  const std::string field_topic(bus::topics::kFieldEstimate.name);
  double field2 = 0.0, roll2 = 0.0;
  std::uint64_t n = 0, cycles = 0, failed = 0;
  recording.forEach(field_topic, [&](std::uint64_t step, const std::string&,
                                     const std::vector<std::uint8_t>& bytes) {
    const auto f = bus::deserialize<FieldDef>(bytes);
    cycles = f.cycles();
    failed = f.failed_cycles();
    const auto it = truth_.find(step);
    const double t_s = static_cast<double>(f.header().sim_time_ns()) * 1e-9;
    if (!f.valid() || it == truth_.end() || t_s < scenario_.acquisition_s) return;
    const double field = (bus::vec3(f.b_body_T()) - it->second.b_B_T).norm() / it->second.b_B_T.norm();
    const double roll = std::remainder(f.roll_rad() - it->second.roll_rad, 2 * kPi);
    field2 += field * field;
    roll2 += roll * roll;
    ++n;
  });
  // Every estimator publishes the topic; a rig without S0 windows gets no S0 keys.
  if (cycles == 0 && failed == 0 && n == 0) return;
  summary["field_error_pct_rms"] = n ? 100.0 * std::sqrt(field2 / n) : NAN;
  summary["alpha_error_deg_rms"] = n ? std::sqrt(roll2 / n) * 180.0 / kPi : NAN;
  summary["s0_windows_solved"] = cycles;
  summary["s0_windows_failed"] = failed;
}

}  // namespace flatsat::analysis
