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
  const double longitude = unwrapped_ - (added_drift_ * t - added_moment_);  // on the first drift's line
  st_ += t;
  sl_ += longitude;
  stt_ += t * t;
  stl_ += t * longitude;
  if (t < params_.window_s) return std::nullopt;

  const double n = count_;
  SynchronousElements mean;
  mean.i = i_sum_ / n;
  mean.e = e_sum_ / n;
  mean.semi_major_axis_m = a_sum_ / n;
  const double denominator = n * stt_ - st_ * st_;
  const double slope = denominator > 0.0 ? (n * stl_ - st_ * sl_) / denominator : 0.0;
  const double intercept = (sl_ - slope * st_) / n;
  mean.drift_rad_s = slope + added_drift_;
  mean.longitude_rad =
      std::remainder(intercept + slope * t + added_drift_ * t - added_moment_, 2.0 * std::numbers::pi);
  reset();
  return mean;
}

void MeanElementsFilter::impulse(const ImpulseEffect& effect, double t_s) {
  i_sum_ += count_ * effect.i;
  e_sum_ += count_ * effect.e;
  const double t = start_s_ ? t_s - *start_s_ : 0.0;
  added_drift_ += effect.drift_rad_s;
  added_moment_ += effect.drift_rad_s * t;
}

}  // namespace flatsat::station_keeping
