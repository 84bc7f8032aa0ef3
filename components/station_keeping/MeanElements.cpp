// SPDX-License-Identifier: Apache-2.0
#include "components/station_keeping/MeanElements.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace flatsat::station_keeping {

std::vector<std::string> validate(const MeanElementsParams& params) {
  if (params.window_s >= 3600.0 && params.window_s <= 864000.0) return {};
  return {"window_s: " + std::to_string(params.window_s) + " is outside [3600, 864000] s"};
}

MeanElementsFilter::MeanElementsFilter(const MeanElementsParams& params) : params_(params) {
  if (const auto problems = validate(params); !problems.empty()) {
    throw std::invalid_argument("mean elements: " + problems.front());
  }
}

void MeanElementsFilter::reset() { *this = MeanElementsFilter(params_); }

std::optional<SynchronousElements> MeanElementsFilter::step(const SynchronousElements& osculating, double t_s) {
  if (!start_s_) {
    start_s_ = t_s;
    last_longitude_ = unwrapped_ = osculating.longitude_rad;
  } else {
    unwrapped_ += std::remainder(osculating.longitude_rad - last_longitude_, 2.0 * std::numbers::pi);
    last_longitude_ = osculating.longitude_rad;
  }
  const double t = t_s - *start_s_;
  ++count_;
  i_sum_ += osculating.i;
  e_sum_ += osculating.e;
  a_sum_ += osculating.semi_major_axis_m;
  // On the line of the window's first drift and longitude.
  const double longitude = unwrapped_ - (added_drift_ * t - added_moment_) - added_jump_;
  const double phase = 2.0 * std::numbers::pi * t / params_.window_s;
  Eigen::Matrix<double, 6, 1> basis;
  basis << 1.0, t / params_.window_s, std::cos(phase), std::sin(phase), std::cos(2.0 * phase), std::sin(2.0 * phase);
  normal_ += basis * basis.transpose();
  moment_ += basis * longitude;
  if (t < params_.window_s) return std::nullopt;

  const double n = count_;
  SynchronousElements mean;
  mean.i = i_sum_ / n;
  mean.e = e_sum_ / n;
  mean.semi_major_axis_m = a_sum_ / n;
  const Eigen::Matrix<double, 6, 1> fit = normal_.ldlt().solve(moment_);
  const double slope = fit(1) / params_.window_s;
  mean.drift_rad_s = slope + added_drift_;
  mean.longitude_rad =
      std::remainder(fit(0) + slope * t + added_drift_ * t - added_moment_ + added_jump_, 2.0 * std::numbers::pi);
  reset();
  return mean;
}

void MeanElementsFilter::impulse(const ImpulseEffect& effect, double t_s) {
  i_sum_ += count_ * effect.i;
  e_sum_ += count_ * effect.e;
  const double t = start_s_ ? t_s - *start_s_ : 0.0;
  added_drift_ += effect.drift_rad_s;
  added_moment_ += effect.drift_rad_s * t;
  added_jump_ += effect.longitude_rad;
}

}  // namespace flatsat::station_keeping
