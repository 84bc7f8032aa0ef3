// SPDX-License-Identifier: Apache-2.0
#include "components/estimator/ReferenceModel.hpp"

#include <stdexcept>

#include "components/common/Validation.hpp"
#include "sim/DynamicsModel.hpp"
#include "sim/SunEphemeris.hpp"

namespace flatsat::estimator {

std::vector<std::string> ReferenceModelParams::validate() const {
  std::vector<std::string> problems;
  for (const auto& p : orbit.validate()) problems.push_back("orbit." + p);
  for (const auto& p : orbit_track.validate()) problems.push_back("orbit_track." + p);
  if (field_harmonics && (field_harmonics->degree < 1 || field_harmonics->degree > 13)) {
    problems.push_back("field_harmonics.degree: must be in 1..13");
  }
  return problems;
}

ReferenceModel::ReferenceModel(const Params& params)
    : params_(validated(params, "ReferenceModelParams")),
      orbit_(params.orbit_track, params.orbit, params.epoch),
      field_(params.field),
      jd_epoch_(sim::julianDate(params.epoch)) {
  if (params.field_harmonics) harmonics_.emplace(*params.field_harmonics);
}

ReferenceVectors ReferenceModel::step(std::int64_t t_ns) {
  const double t_s = sim::toSeconds(t_ns);
  const double jd = jd_epoch_ + t_s / 86400.0;
  const auto state = orbit_.at(t_s);
  const Eigen::Vector3d& r_N = state.r_N_m;
  const Eigen::Matrix3d R_EN = sim::R_EN(jd);
  ReferenceVectors out;
  const Eigen::Vector3d r_E = R_EN * r_N;
  out.b_N_T = R_EN.transpose() * (harmonics_ ? harmonics_->b_E_T(r_E) : field_.b_E_T(r_E));
  out.orbit_normal_N_unit = r_N.cross(state.v_N_m_s).normalized();
  out.r_N_m = r_N;
  out.v_N_m_s = state.v_N_m_s;
  out.sun_N_unit =
      (sim::sunPosition_N_m(jd + sim::kTtMinusUtc_s / 86400.0) - r_N).normalized();
  return out;
}

}  // namespace flatsat::estimator
