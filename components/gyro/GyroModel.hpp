// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/common/GaussianNoise.hpp"

namespace flatsat::gyro {

/// Rate-integrating gyro triad, Farrenkopf noise model (white rate noise + random-walk bias),
/// with scale-factor and misalignment errors.
struct GyroParams {
  double angle_random_walk_rad_per_sqrt_s = 4.363e-5;     // [rad/√s] ARW σ_v (0.15 °/√h), >= 0
  double rate_random_walk_rad_per_s_sqrt_s = 1.0e-6;      // [rad/s/√s] bias drift σ_u, >= 0
  Eigen::Vector3d bias0_B_rad_s = Eigen::Vector3d::Zero();  // [rad/s] bias at reset, finite
  std::uint64_t seed = 3;                                   // [-] noise seed, any value
  Eigen::Vector3d scale_factor = Eigen::Vector3d::Zero();   // [-] error per axis (100 ppm = 1e-4), each in (-0.1, 0.1)
  Eigen::Vector3d misalignment_rad = Eigen::Vector3d::Zero();  // [rad] small rotation of the triad from body axes, each in (-0.1, 0.1)

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// [rad/s] true body rate relative to inertial, body axes.
struct GyroInput {
  Eigen::Vector3d w_NB_B_rad_s = Eigen::Vector3d::Zero();
};

struct GyroOutput {
  Eigen::Vector3d w_NB_B_rad_s = Eigen::Vector3d::Zero();  // [rad/s] measured body rate
  Eigen::Vector3d bias_B_rad_s = Eigen::Vector3d::Zero();  // [rad/s] true bias at this sample (recording only)
};

/// Each sample is the mean rate over the interval since the previous call; the interval comes
/// from the time argument. The first call (and any call whose time does not advance) has no
/// interval: it returns truth + bias, without white noise or drift.
class GyroModel {
 public:
  using Params = GyroParams;
  using Input = GyroInput;
  using Output = GyroOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit GyroModel(const Params& params);

  /// Restores bias0, forgets the previous sample time and replays the noise sequence.
  void reset();

  /// @param t_ns [ns] sample time; the difference to the previous call is the interval.
  Output step(const Input& in, std::int64_t t_ns);

  const Params& params() const { return params_; }

 private:
  Params params_;
  Eigen::Matrix3d sensed_from_true_;  // (I + diag(scale factor))(I − [misalignment×])
  GaussianNoise noise_;
  Eigen::Vector3d bias_B_rad_s_;
  std::int64_t last_t_ns_ = 0;
  bool has_last_t_ = false;
};

}  // namespace flatsat::gyro
