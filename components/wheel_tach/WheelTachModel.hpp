// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/common/GaussianNoise.hpp"

namespace flatsat::wheel_tach {

/// Reaction-wheel tachometers, one per active wheel.
struct WheelTachParams {
  int wheel_count = 3;            // [-] active wheels (slots 0..wheel_count-1), 1..4
  double noise_rad_s = 0.01;      // [rad/s] 1σ white noise per wheel, >= 0
  double quantum_rad_s = 0.0;     // [rad/s] speed resolution, 0 = continuous, >= 0
  std::uint64_t seed = 4;         // [-] noise seed, any value

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// [rad/s] true wheel speeds relative to the body; slots beyond wheel_count are ignored.
struct WheelTachInput {
  Eigen::Vector4d wheel_speed_rad_s = Eigen::Vector4d::Zero();
};

/// [rad/s] measured wheel speeds; slots beyond wheel_count are zero.
struct WheelTachOutput {
  Eigen::Vector4d wheel_speed_rad_s = Eigen::Vector4d::Zero();
};

/// Ω_meas = quantize(Ω + noise) per active wheel.
class WheelTachModel {
 public:
  using Params = WheelTachParams;
  using Input = WheelTachInput;
  using Output = WheelTachOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit WheelTachModel(const Params& params);

  /// Replays the noise sequence from the seed.
  void reset();

  /// The sample does not depend on time; t_ns [ns] is kept for the common API.
  Output step(const Input& in, std::int64_t t_ns);

  const Params& params() const { return params_; }

 private:
  Params params_;
  GaussianNoise noise_;
};

}  // namespace flatsat::wheel_tach
