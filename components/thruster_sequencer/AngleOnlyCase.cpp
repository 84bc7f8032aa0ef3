// SPDX-License-Identifier: Apache-2.0
#include "components/thruster_sequencer/AngleOnlyCase.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Dense>

namespace flatsat::thruster_sequencer {

AngleOnlyCaseResult runAngleOnlyCase(const AngleOnlySequencerParams& params, const AngleOnlyCaseSetup& setup) {
  AngleOnlySequencer sequencer(params);
  const sim::Thrusters thrusters(params.thrusters);
  const Eigen::Vector3d& a = params.axis_B;
  const Eigen::Vector3d& b = params.boresight_B;
  const Eigen::Matrix3d inverse_inertia = params.inertia_B_kg_m2.inverse();
  const double dt = params.step_s;
  const auto steps = static_cast<std::int64_t>(std::llround(setup.duration_s / dt));
  const auto& cycle = params.cycle;
  const double margin = std::max(std::abs(sequencer.pulseDeltaRate_rad_s(1)),
                                 std::abs(sequencer.pulseDeltaRate_rad_s(-1))) *
                      (dt + std::ceil(params.pulse_on_time_s / (params.max_duty * dt) - 1e-9) * dt);

  AngleOnlyCaseResult result;
  double angle = setup.angle0_rad;
  double rate = setup.rate0_rad_s;
  std::int64_t inside_since = 0;  // first step of the current run inside the range
  for (std::int64_t k = 0; k < steps; ++k) {
    const double t = static_cast<double>(k) * dt;
    const Eigen::Vector3d sun_B = b * std::cos(angle) + b.cross(a) * std::sin(angle);
    const bool seen = std::abs(angle) < setup.fov_half_angle_rad;
    const auto out = sequencer.step({sun_B, seen}, std::llround(t * 1e9));
    result.pulses.add(out.cycle);
    if (angle > cycle.upper_limit_rad + margin || angle < cycle.lower_limit_rad - margin) {
      inside_since = k + 1;
      result.pulses_to_settle = result.pulses.total;
    }
    result.max_angle_rad = std::max(result.max_angle_rad, std::abs(angle - cycle.target_rad));
    const auto fired = thrusters.fire(out.on_time_s, sim::ThrusterGimbals::Zero(), dt);
    const double acceleration = a.dot(inverse_inertia * (fired.torque_B_Nm + setup.disturbance_Nm * a));
    angle += rate * dt + 0.5 * acceleration * dt * dt;
    rate += acceleration * dt;
  }
  result.final_angle_rad = angle;
  result.final_rate_rad_s = rate;
  result.settle_time_s = static_cast<double>(inside_since) * dt;
  result.settled = inside_since <= steps - steps / 4 && angle <= cycle.upper_limit_rad + margin &&
                   angle >= cycle.lower_limit_rad - margin;
  return result;
}

std::vector<AngleOnlyCaseSetup> seededCases(std::uint64_t seed, int count, double max_angle_rad,
                                            double max_rate_rad_s, double disturbance_Nm, double duration_s) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(-max_angle_rad, max_angle_rad);
  std::uniform_real_distribution<double> rate(-max_rate_rad_s, max_rate_rad_s);
  std::vector<AngleOnlyCaseSetup> cases;
  for (int i = 0; i < count; ++i) {
    AngleOnlyCaseSetup c;
    c.angle0_rad = angle(rng);
    c.rate0_rad_s = rate(rng);
    c.disturbance_Nm = disturbance_Nm;
    c.duration_s = duration_s;
    cases.push_back(c);
  }
  return cases;
}

}  // namespace flatsat::thruster_sequencer
