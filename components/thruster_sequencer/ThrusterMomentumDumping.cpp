// SPDX-License-Identifier: Apache-2.0
#include "components/thruster_sequencer/ThrusterMomentumDumping.hpp"

#include <algorithm>
#include <stdexcept>

#include "components/common/Validation.hpp"
#include "components/thruster_sequencer/AngleOnlySequencer.hpp"

namespace flatsat::thruster_sequencer {

std::vector<std::string> ThrusterMomentumDumpingParams::validate() const {
  std::vector<std::string> errors;
  append(errors, wheels.validate("wheels"));
  requirePositive(errors, "h_stop_Nms", h_stop_Nms);
  require(errors, h_start_Nms > h_stop_Nms && std::isfinite(h_start_Nms), "h_start_Nms",
          "must be finite and > h_stop_Nms");
  requirePositive(errors, "force_weight_m", force_weight_m);
  require(errors, !thrusters.empty() && thrusters.size() <= static_cast<std::size_t>(sim::kMaxThrusters),
          "thrusters", "1 to kMaxThrusters (12) needed");
  for (const auto& e : PulseShaperParams{step_s, max_duty, minOnTimes_s(thrusters)}.validate()) {
    errors.push_back("shaper." + e);
  }
  return errors;
}

ThrusterMomentumDumping::ThrusterMomentumDumping(const Params& params)
    : params_(params), shaper_({params.step_s, params.max_duty, minOnTimes_s(params.thrusters)}) {
  if (const auto errors = params_.validate(); !errors.empty()) {
    std::string message = "ThrusterMomentumDumpingParams invalid:";
    for (const auto& e : errors) message += " " + e + ";";
    throw std::invalid_argument(message);
  }
}

void ThrusterMomentumDumping::reset() {
  dumping_ = false;
  shaper_.reset();
}

ThrusterMomentumDumpingOutput ThrusterMomentumDumping::step(const Eigen::Vector4d& wheel_speed_rad_s,
                                                            std::int64_t /*t_ns*/) {
  Output out;
  out.h_B_Nms = params_.wheels.momentum_B_Nms(wheel_speed_rad_s);
  const double h = out.h_B_Nms.norm();
  if (h > params_.h_start_Nms) {
    dumping_ = true;
  } else if (h < params_.h_stop_Nms) {
    dumping_ = false;
  }
  sim::ThrusterVector request = sim::ThrusterVector::Zero();
  if (dumping_ && h > 0.0) {
    const ThrusterFiring firing = selectThrusters(params_.thrusters, -out.h_B_Nms, params_.force_weight_m);
    // The last step fires only what is left above zero, so the dump does not overshoot:
    // the firing's torque along −H, τ_u, over t gives τ_u t of the |H| to remove.
    const double torque_along = -firing.torque_B_Nm.dot(out.h_B_Nms) / h;
    if (firing.possible() && torque_along > 0.0) {
      const double duty_s = std::min(params_.max_duty * params_.step_s, h / torque_along);
      request = firing.weight * duty_s;
      out.torque_B_Nm = firing.torque_B_Nm * duty_s / params_.step_s;
    }
  }
  out.on_time_s = shaper_.step(request);
  out.active = dumping_;
  return out;
}

}  // namespace flatsat::thruster_sequencer
