// SPDX-License-Identifier: Apache-2.0
#include "components/thruster_sequencer/AngleOnlySequencer.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

#include "components/common/Validation.hpp"

namespace flatsat::thruster_sequencer {

namespace {

PulseShaperParams shaperParams(const AngleOnlySequencerParams& p) {
  return {p.step_s, p.max_duty, minOnTimes_s(p.thrusters)};
}

}  // namespace

sim::ThrusterVector minOnTimes_s(const std::vector<sim::ThrusterParams>& thrusters) {
  sim::ThrusterVector t = sim::ThrusterVector::Zero();
  for (std::size_t i = 0; i < thrusters.size() && i < static_cast<std::size_t>(sim::kMaxThrusters); ++i) {
    if (thrusters[i].thrust_N > 0.0) t(static_cast<Eigen::Index>(i)) = thrusters[i].min_impulse_bit_Ns / thrusters[i].thrust_N;
  }
  return t;
}

double angleAboutAxis_rad(const Eigen::Vector3d& sun_B, const Eigen::Vector3d& boresight_B,
                          const Eigen::Vector3d& axis_B) {
  return std::atan2(sun_B.dot(boresight_B.cross(axis_B)), sun_B.dot(boresight_B));
}

std::vector<std::string> AngleOnlySequencerParams::validate() const {
  std::vector<std::string> errors;
  for (const auto& e : cycle.validate()) errors.push_back("cycle." + e);
  requireUnit(errors, "axis_B", axis_B);
  requireUnit(errors, "boresight_B", boresight_B);
  require(errors, std::abs(axis_B.dot(boresight_B)) < 1e-6, "boresight_B", "must be ⟂ axis_B");
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(inertia_B_kg_m2);
  require(errors, inertia_B_kg_m2.allFinite() && inertia_B_kg_m2.isApprox(inertia_B_kg_m2.transpose()) &&
                      eigen.eigenvalues().minCoeff() > 0.0,
          "inertia_B_kg_m2", "must be symmetric positive definite");
  requirePositive(errors, "pulse_on_time_s", pulse_on_time_s);
  requirePositive(errors, "force_weight_m", force_weight_m);
  for (const auto& e : shaperParams(*this).validate()) errors.push_back("shaper." + e);
  require(errors, thrusters.size() <= static_cast<std::size_t>(sim::kMaxThrusters), "thrusters",
          "at most kMaxThrusters (12)");
  if (errors.empty()) {
    for (const int sense : {1, -1}) {
      require(errors, selectThrusters(thrusters, sense * axis_B, force_weight_m).possible(), "thrusters",
              sense > 0 ? "no live thruster turns the body about +axis" : "no live thruster turns the body about -axis");
    }
  }
  return errors;
}

AngleOnlySequencer::AngleOnlySequencer(const Params& params)
    : params_(params), cycle_(params.cycle), shaper_(shaperParams(params)) {
  if (const auto errors = params_.validate(); !errors.empty()) {
    std::string message = "AngleOnlySequencerParams invalid:";
    for (const auto& e : errors) message += " " + e + ";";
    throw std::invalid_argument(message);
  }
  raise_ = selectThrusters(params_.thrusters, params_.axis_B, params_.force_weight_m);
  lower_ = selectThrusters(params_.thrusters, -params_.axis_B, params_.force_weight_m);
}

void AngleOnlySequencer::reset() {
  cycle_.reset();
  shaper_.reset();
}

double AngleOnlySequencer::pulseDeltaRate_rad_s(int sense) const {
  // Euler's equation over a pulse short against the motion: I Δω = τ t_on.
  const Eigen::Vector3d angular_impulse = firing(sense).torque_B_Nm * params_.pulse_on_time_s;
  return params_.axis_B.dot(params_.inertia_B_kg_m2.ldlt().solve(angular_impulse));
}

AngleOnlySequencerOutput AngleOnlySequencer::step(const Input& in, std::int64_t t_ns) {
  Output out;
  out.angle_rad = angleAboutAxis_rad(in.sun_B_unit, params_.boresight_B, params_.axis_B);
  out.cycle = cycle_.step({out.angle_rad, in.valid}, t_ns);
  sim::ThrusterVector request = sim::ThrusterVector::Zero();
  if (out.cycle.pulse != 0) request = firing(out.cycle.pulse).weight * params_.pulse_on_time_s;
  out.on_time_s = shaper_.step(request);
  return out;
}

}  // namespace flatsat::thruster_sequencer
