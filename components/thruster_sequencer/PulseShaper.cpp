// SPDX-License-Identifier: Apache-2.0
#include "components/thruster_sequencer/PulseShaper.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "components/common/Validation.hpp"

namespace flatsat::thruster_sequencer {

namespace {

// An owed on-time meant as k whole minimum pulses may be a rounding error short of k.
constexpr double kPulseCountTolerance = 1e-9;

}  // namespace

std::vector<std::string> PulseShaperParams::validate() const {
  std::vector<std::string> errors;
  requirePositive(errors, "step_s", step_s);
  require(errors, max_duty > 0.0 && max_duty <= 1.0, "max_duty", "must be in (0, 1]");
  require(errors, min_on_time_s.allFinite() && min_on_time_s.minCoeff() >= 0.0, "min_on_time_s",
          "every thruster's must be finite and >= 0");
  require(errors, !(min_on_time_s.maxCoeff() > max_duty * step_s), "min_on_time_s",
          "must fit in max_duty * step_s");
  return errors;
}

PulseShaper::PulseShaper(const Params& params) : params_(validated(params, "PulseShaperParams invalid")) {
}

void PulseShaper::reset() { owed_s_.setZero(); }

sim::ThrusterVector PulseShaper::step(const sim::ThrusterVector& request_s) {
  sim::ThrusterVector on_time_s = sim::ThrusterVector::Zero();
  const double longest_s = params_.max_duty * params_.step_s;
  for (int i = 0; i < sim::kMaxThrusters; ++i) {
    const double request = request_s(i);
    if (std::isfinite(request) && request > 0.0) owed_s_(i) += request;
    double fire = std::min(owed_s_(i), longest_s);
    const double t_min = params_.min_on_time_s(i);
    if (t_min > 0.0) fire = t_min * std::floor(fire / t_min + kPulseCountTolerance);
    on_time_s(i) = fire;
    owed_s_(i) = std::max(owed_s_(i) - fire, 0.0);
  }
  return on_time_s;
}

}  // namespace flatsat::thruster_sequencer
