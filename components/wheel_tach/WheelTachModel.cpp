// SPDX-License-Identifier: Apache-2.0
#include "components/wheel_tach/WheelTachModel.hpp"

#include <cmath>
#include <stdexcept>

#include "components/common/Validation.hpp"

namespace flatsat::wheel_tach {

std::vector<std::string> WheelTachParams::validate() const {
  std::vector<std::string> errors;
  requireInRange(errors, "wheel_count", wheel_count, 1, 4);
  requireNonNegative(errors, "noise_rad_s", noise_rad_s);
  requireNonNegative(errors, "quantum_rad_s", quantum_rad_s);
  return errors;
}

WheelTachModel::WheelTachModel(const Params& params) : params_(params), noise_(params.seed) {
  if (const auto errors = params_.validate(); !errors.empty()) {
    std::string message = "WheelTachParams invalid:";
    for (const auto& e : errors) {
      message += " " + e + ";";
    }
    throw std::invalid_argument(message);
  }
}

void WheelTachModel::reset() { noise_.reset(); }

WheelTachOutput WheelTachModel::step(const Input& in, std::int64_t /*t_ns*/) {
  Output out;
  for (int i = 0; i < params_.wheel_count; ++i) {
    double speed = in.wheel_speed_rad_s[i] + noise_.sample(params_.noise_rad_s);
    if (params_.quantum_rad_s > 0.0) {
      speed = params_.quantum_rad_s * std::round(speed / params_.quantum_rad_s);
    }
    out.wheel_speed_rad_s[i] = speed;
  }
  return out;
}

}  // namespace flatsat::wheel_tach
