// SPDX-License-Identifier: Apache-2.0
#include "components/thruster_sequencer/StationKeepingFirings.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "components/common/Validation.hpp"

namespace flatsat::thruster_sequencer {

namespace {

/// [rad] angle_rad wrapped to [0, 2π).
double wrapPositive(double angle_rad) {
  const double wrapped = std::fmod(angle_rad, 2.0 * std::numbers::pi);
  return wrapped < 0.0 ? wrapped + 2.0 * std::numbers::pi : wrapped;
}

}  // namespace

std::vector<std::string> StationKeepingFiringsParams::validate() const {
  std::vector<std::string> problems;
  if (!(step_s > 0.0 && step_s <= 3600.0)) problems.push_back("step_s: outside (0, 3600] s");
  if (!(ra_rate_rad_s > 0.0 && ra_rate_rad_s <= 0.01)) problems.push_back("ra_rate_rad_s: outside (0, 0.01] rad/s");
  if (thruster_count < 1 || thruster_count > sim::kMaxThrusters) {
    problems.push_back("thruster_count: outside 1.." + std::to_string(sim::kMaxThrusters));
  }
  return problems;
}

StationKeepingFirings::StationKeepingFirings(const StationKeepingFiringsParams& params)
    : params_(validated(params, "station-keeping firings")) {}

void StationKeepingFirings::reset() {
  pending_.clear();
  has_plan_ = false;
  plan_step_ = 0;
}

void StationKeepingFirings::plan(std::uint64_t plan_step, const std::vector<ScheduledFiring>& firings) {
  if (has_plan_ && plan_step == plan_step_) return;
  has_plan_ = true;
  plan_step_ = plan_step;
  std::erase_if(pending_, [](const Pending& p) { return !p.burning; });
  for (const auto& f : firings) {
    if (f.thruster < 0 || f.thruster >= params_.thruster_count || !(f.duration_s > 0.0)) continue;
    pending_.push_back({f, f.duration_s, false});
  }
}

StationKeepingFiringsOutput StationKeepingFirings::step(double ra_rad) {
  StationKeepingFiringsOutput out;
  sim::ThrusterVector& on = out.on_time_s;
  for (auto& p : pending_) {
    if (!p.burning) {
      const double half_arc = 0.5 * p.firing.duration_s * params_.ra_rate_rad_s;
      const double into_arc = wrapPositive(ra_rad - (p.firing.ra_rad - half_arc));
      // Up to the centre, or one step's sweep for a burn shorter than two steps.
      p.burning = into_arc <= std::max(half_arc, params_.step_s * params_.ra_rate_rad_s);
    }
    if (!p.burning) continue;
    const double on_s = std::min(p.remaining_s, params_.step_s);
    on(p.firing.thruster) = std::min(params_.step_s, on(p.firing.thruster) + on_s);
    if (p.firing.dumps) out.dump_left_s(p.firing.thruster) = std::max(out.dump_left_s(p.firing.thruster), p.remaining_s);
    p.remaining_s -= on_s;
  }
  std::erase_if(pending_, [](const Pending& p) { return p.remaining_s <= 0.0; });
  return out;
}

}  // namespace flatsat::thruster_sequencer
