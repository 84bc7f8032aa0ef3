// SPDX-License-Identifier: Apache-2.0
#include "components/common/onboard/ReferenceModel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "components/common/Validation.hpp"
#include "sim/DynamicsModel.hpp"
#include "sim/SunEphemeris.hpp"

namespace flatsat::onboard {

std::vector<std::string> ReferenceModelParams::validate() const {
  std::vector<std::string> problems;
  for (const auto& p : orbit.validate()) problems.push_back("orbit." + p);
  for (const auto& p : orbit_track.validate()) problems.push_back("orbit_track." + p);
  if (field_harmonics && (field_harmonics->degree < 1 || field_harmonics->degree > 13)) {
    problems.push_back("field_harmonics.degree: must be in 1..13");
  }
  if (!(field_node_s >= 0.0 && field_node_s <= 10.0)) problems.push_back("field_node_s: must be in 0..10 s");
  return problems;
}

ReferenceModelParams referenceModelOf(const vehicle::VehicleDescription& onboard, double field_node_s) {
  ReferenceModelParams p;
  p.epoch = onboard.epoch;
  p.orbit = onboard.orbit;
  p.orbit_track = onboard.orbit_track;
  p.field = onboard.field.dipole;
  p.field_node_s = field_node_s;
  // A numerical propagator's drag uses the density model the onboard view carries.
  if (onboard.atmosphere) p.orbit_track.forces.atmosphere = *onboard.atmosphere;
  if (onboard.field.spherical_harmonics) {
    auto harmonics = onboard.field.harmonics;
    harmonics.degree = std::min(harmonics.degree, onboard.field.degree);
    p.field_harmonics = harmonics;
  }
  p.field_spot = onboard.field.spot;
  return p;
}

ReferenceModel::ReferenceModel(const Params& params)
    : params_(validated(params, "ReferenceModelParams")),
      orbit_(params.orbit_track, params.orbit, params.epoch),
      field_(params.field),
      jd_epoch_(sim::julianDate(params.epoch)) {
  if (params.field_harmonics) harmonics_.emplace(*params.field_harmonics);
}

Eigen::Vector3d ReferenceModel::fieldAt(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s, double jd) const {
  if (params_.field_spot) {
    return sim::R_NO(r_N_m, v_N_m_s) *
           params_.field_spot->b_O_T(sim::argumentOfLatitude_rad(r_N_m, v_N_m_s), r_N_m.norm());
  }
  const Eigen::Matrix3d R_EN = sim::R_EN(jd);
  const Eigen::Vector3d r_E = R_EN * r_N_m;
  return R_EN.transpose() * (harmonics_ ? harmonics_->b_E_T(r_E) : field_.b_E_T(r_E));
}

Eigen::Vector3d ReferenceModel::sunAt(double t_s) const {
  return sim::sunPosition_N_m(jd_epoch_ + (t_s + sim::kTtMinusUtc_s) / 86400.0);
}

bool ReferenceModel::takeNodes(double t_s) {
  const double h = params_.field_node_s;
  if (h <= 0.0) return false;
  const auto j = static_cast<long long>(std::floor(t_s / h));
  if (nodes_ == 0 || node_[2].index != j) {
    // t_j <= t_s, and after every earlier call's time: the orbit is still asked in order.
    const double t_j = static_cast<double>(j) * h;
    const auto state = orbit_.at(t_j);
    const Node node{j, fieldAt(state.r_N_m, state.v_N_m_s, jd_epoch_ + t_j / 86400.0), sunAt(t_j)};
    node_ = {node_[1], node_[2], node};
    nodes_ = std::min(nodes_ + 1, 3);
  }
  return nodes_ == 3 && node_[0].index == j - 2 && node_[1].index == j - 1;
}

Eigen::Vector3d ReferenceModel::extrapolated(double t_s, Eigen::Vector3d Node::*quantity) const {
  // Lagrange through x = −2, −1, 0 at x = τ.
  const double tau = t_s / params_.field_node_s - static_cast<double>(node_[2].index);
  return 0.5 * tau * (tau + 1.0) * (node_[0].*quantity) - tau * (tau + 2.0) * (node_[1].*quantity) +
         0.5 * (tau + 1.0) * (tau + 2.0) * (node_[2].*quantity);
}

ReferenceVectors ReferenceModel::step(std::int64_t t_ns) {
  const double t_s = sim::toSeconds(t_ns);
  const bool from_nodes = takeNodes(t_s);  // before orbit_.at(t_s): it may ask for t_j <= t_s
  const auto state = orbit_.at(t_s);
  const Eigen::Vector3d& r_N = state.r_N_m;
  ReferenceVectors out;
  out.b_N_T = from_nodes ? extrapolated(t_s, &Node::b_N_T) : fieldAt(r_N, state.v_N_m_s, jd_epoch_ + t_s / 86400.0);
  out.orbit_normal_N_unit = r_N.cross(state.v_N_m_s).normalized();
  out.r_N_m = r_N;
  out.v_N_m_s = state.v_N_m_s;
  out.sun_N_unit = ((from_nodes ? extrapolated(t_s, &Node::r_sun_N_m) : sunAt(t_s)) - r_N).normalized();
  return out;
}

}  // namespace flatsat::onboard
