// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/common/GaussianNoise.hpp"

namespace flatsat::sun_sensor {

/// Fine two-axis sun sensor.
struct SunSensorParams {
  Eigen::Vector3d boresight_B = Eigen::Vector3d::UnitX();  // [-] boresight in body axes, unit length
  double noise_rad = 1.0e-4;                               // [rad] 1σ noise of each transverse angle, >= 0
  double fov_half_angle_rad = 1.0471975511965976;          // [rad] cone half-angle (60°), (0, π/2)
  double min_illumination = 0.5;                           // [-] below this Sun fraction: no Sun, [0, 1]
  std::uint64_t seed = 2;                                  // [-] noise seed, any value

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct SunSensorInput {
  Eigen::Vector3d sun_B_unit = Eigen::Vector3d::UnitX();  // [-] true Sun direction in body axes
  double illumination = 1.0;                              // [-] visible fraction of the solar disc, 0 = umbra
};

struct SunSensorOutput {
  Eigen::Vector3d sun_B_unit = Eigen::Vector3d::Zero();  // [-] measured Sun direction; zero when !valid
  bool valid = false;                                    // Sun lit enough and inside the field of view
};

/// Measures the two angles of the Sun from the boresight, α = atan2(s·t1, s·b) and
/// β = atan2(s·t2, s·b) with t1, t2 the transverse axes, adds independent noise to each
/// and rebuilds the unit vector from their tangents, the quantities a two-axis slit or
/// quadrant sensor resolves (Wertz (ed.), Spacecraft Attitude Determination and Control,
/// 1978, §7.1 Sun sensor models).
class SunSensorModel {
 public:
  using Params = SunSensorParams;
  using Input = SunSensorInput;
  using Output = SunSensorOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit SunSensorModel(const Params& params);

  /// Replays the noise sequence from the seed.
  void reset();

  /// The sample does not depend on time; t_ns [ns] is kept for the common API.
  Output step(const Input& in, std::int64_t t_ns);

  const Params& params() const { return params_; }
  /// [-] first transverse axis t1 (α is measured towards it); t2 = boresight × t1.
  const Eigen::Vector3d& transverse1_B() const { return t1_B_; }
  const Eigen::Vector3d& transverse2_B() const { return t2_B_; }

 private:
  Params params_;
  Eigen::Vector3d t1_B_;
  Eigen::Vector3d t2_B_;
  double cos_fov_;
  GaussianNoise noise_;
};

}  // namespace flatsat::sun_sensor
