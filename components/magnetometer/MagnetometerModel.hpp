// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/common/GaussianNoise.hpp"

namespace flatsat::magnetometer {

/// Three-axis magnetometer error model.
struct MagnetometerParams {
  double noise_T = 1.0e-7;                                   // [T] 1σ white noise per axis, >= 0
  Eigen::Vector3d bias_B_T = Eigen::Vector3d::Zero();        // [T] constant bias per body axis, finite
  Eigen::Vector3d scale_factor = Eigen::Vector3d::Ones();    // [-] gain per body axis, > 0
  double quantum_T = 0.0;                                    // [T] ADC step, 0 = continuous, >= 0
  double range_T = 1.0e-4;                                   // [T] full scale: each axis clips at ±range_T, > 0
  std::uint64_t seed = 1;                                    // [-] noise seed, any value
  Eigen::Vector3d misalignment_rad = Eigen::Vector3d::Zero(); // [rad] rotation vector body → sensor axes, |·| < π
  Eigen::Matrix3d coil_coupling_T_per_Am2 = Eigen::Matrix3d::Zero();  // [T/(A m²)] field the torquers put on the sensor per unit dipole, finite
  bool blank_while_coils_on = false;                         // [-] flag a sample taken with a coil on as blanked

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct MagnetometerInput {
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();         // [T] true geomagnetic field, body axes
  Eigen::Vector3d dipole_B_Am2 = Eigen::Vector3d::Zero();  // [A m²] torquer dipole on at the sample instant
};

struct MagnetometerOutput {
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();  // [T] measured field in body axes
  bool saturated = false;                           // at least one axis clipped at ±range_T
  bool blanked = false;                             // blank_while_coils_on and a coil was on: not a measurement
};

/// b_meas = quantize(scale ⊙ (R_mis (b + C m)) + bias + noise), clipped per axis to
/// the range: R_mis turns body into sensor axes (the mounting error, reported in body
/// axes as the rig has no other frame for it), C m is the torquers' own field at the
/// sensor. Blanking (the usual flight answer to C m, with the unloading controller's
/// quiet part) marks the sample instead of hiding it.
class MagnetometerModel {
 public:
  using Params = MagnetometerParams;
  using Input = MagnetometerInput;
  using Output = MagnetometerOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit MagnetometerModel(const Params& params);

  /// Replays the noise sequence from the seed.
  void reset();

  /// The sample does not depend on time; t_ns [ns] is kept for the common API.
  Output step(const Input& in, std::int64_t t_ns);

  const Params& params() const { return params_; }

 private:
  Params params_;
  GaussianNoise noise_;
};

}  // namespace flatsat::magnetometer
