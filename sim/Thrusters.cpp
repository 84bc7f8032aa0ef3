// SPDX-License-Identifier: Apache-2.0
#include "sim/Thrusters.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <Eigen/Geometry>

#include "sim/Format.hpp"

namespace flatsat::sim {
namespace {

constexpr double kUnitNormTolerance = 1e-6;
// An on-time meant as a whole number of minimum pulses (k·t_min) may arrive a
// rounding error short of it; without this allowance ⌊·⌋ would drop a pulse.
constexpr double kPulseCountTolerance = 1e-9;

bool isUnit(const Eigen::Vector3d& v) { return v.allFinite() && std::abs(v.norm() - 1.0) <= kUnitNormTolerance; }

// A non-finite command counts as zero (then limited like any other).
double clampedOrZero(double value, double low, double high) {
  return std::clamp(std::isfinite(value) ? value : 0.0, low, high);
}

}  // namespace

std::vector<std::string> ThrusterParams::validate() const {
  std::vector<std::string> errors;
  if (!r_B_m.allFinite()) errors.push_back("r_B_m: must be finite");
  if (!isUnit(direction_B)) {
    errors.push_back("direction_B: must be a unit vector (norm " + formatNumber(direction_B.norm()) + ")");
  }
  if (!(thrust_N > 0.0) || !std::isfinite(thrust_N)) errors.push_back("thrust_N: " + formatNumber(thrust_N) + " must be > 0");
  if (!(min_impulse_bit_Ns >= 0.0) || !std::isfinite(min_impulse_bit_Ns)) {
    errors.push_back("min_impulse_bit_Ns: " + formatNumber(min_impulse_bit_Ns) + " must be ≥ 0");
  }
  if (!gimballed) return errors;
  if (!isUnit(gimbal_axis1_B)) errors.push_back("gimbal_axis1_B: must be a unit vector");
  if (!isUnit(gimbal_axis2_B)) errors.push_back("gimbal_axis2_B: must be a unit vector");
  for (int k = 0; k < 2; ++k) {
    const std::string angle = k == 0 ? "[0]" : "[1]";
    const double low = gimbal_min_rad(k);
    const double high = gimbal_max_rad(k);
    if (!std::isfinite(low) || low < -std::numbers::pi) {
      errors.push_back("gimbal_min_rad" + angle + ": " + formatNumber(low) + " must be finite and ≥ −π");
    }
    if (!std::isfinite(high) || high > std::numbers::pi) {
      errors.push_back("gimbal_max_rad" + angle + ": " + formatNumber(high) + " must be finite and ≤ π");
    }
    if (low > high) errors.push_back("gimbal_max_rad" + angle + ": must be ≥ gimbal_min_rad" + angle);
  }
  return errors;
}

Thrusters::Thrusters(std::vector<ThrusterParams> thrusters)
    : thrusters_(std::move(thrusters)), count_(std::min(static_cast<int>(thrusters_.size()), kMaxThrusters)) {}

Eigen::Vector3d Thrusters::direction_B(int i, const Eigen::Vector2d& gimbal_rad) const {
  const ThrusterParams& t = thrusters_[static_cast<std::size_t>(i)];
  if (!t.gimballed) return t.direction_B;
  return Eigen::AngleAxisd(gimbal_rad(0), t.gimbal_axis1_B) *
         (Eigen::AngleAxisd(gimbal_rad(1), t.gimbal_axis2_B) * t.direction_B);
}

ThrusterOutput Thrusters::fire(const ThrusterVector& on_time_s, const ThrusterGimbals& gimbal_rad, double dt_s) const {
  ThrusterOutput out;
  if (!(dt_s > 0.0)) return out;
  for (int i = 0; i < count_; ++i) {
    const ThrusterParams& t = thrusters_[static_cast<std::size_t>(i)];
    if (t.gimballed) {
      for (int k = 0; k < 2; ++k) {
        out.gimbal_rad(k, i) = clampedOrZero(gimbal_rad(k, i), t.gimbal_min_rad(k), t.gimbal_max_rad(k));
      }
    }
    if (t.failed) continue;
    double on_time = clampedOrZero(on_time_s(i), 0.0, dt_s);
    if (t.min_impulse_bit_Ns > 0.0) {
      const double min_on_time = t.min_impulse_bit_Ns / t.thrust_N;
      on_time = min_on_time * std::floor(on_time / min_on_time + kPulseCountTolerance);
    }
    if (on_time <= 0.0) continue;
    const Eigen::Vector3d impulse = t.thrust_N * on_time * direction_B(i, out.gimbal_rad.col(i));
    out.on_time_s(i) = on_time;
    out.impulse_Ns(i) = t.thrust_N * on_time;
    out.force_B_N += impulse / dt_s;
    out.torque_B_Nm += t.r_B_m.cross(impulse) / dt_s;
  }
  return out;
}

}  // namespace flatsat::sim
