// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "components/common/GaussianNoise.hpp"

namespace flatsat::star_tracker {

/// Star tracker head, as a datasheet gives it (e.g. Sodern Hydra, Jena-Optronik Astro APS:
/// a few arcsec across the boresight, several times that about it; Sun exclusion ~30-45°,
/// Earth limb exclusion ~20-30°, tracking up to a few deg/s).
struct StarTrackerParams {
  Eigen::Quaterniond q_body_sensor = Eigen::Quaterniond::Identity();  // [-] sensor → body; the boresight is sensor +z
  /// [-] unit; the mounting the unit's configuration turns its attitude into body axes with
  /// (the vehicle's onboard view); nullopt: q_body_sensor. A wrong one rotates every solution
  /// by q_body_sensor ⊗ q_body_sensor_onboard⁻¹ in body axes.
  std::optional<Eigen::Quaterniond> q_body_sensor_onboard;
  double noise_cross_rad = 2.0e-5;         // [rad] 1σ about each axis across the boresight (4 arcsec), >= 0
  double noise_about_rad = 1.5e-4;         // [rad] 1σ about the boresight (30 arcsec), >= 0
  double max_rate_rad_s = 0.035;           // [rad/s] no solution above this body rate (2 deg/s), > 0
  double sun_exclusion_rad = 0.6108652382; // [rad] no solution with the Sun this close to the boresight (35°), [0, π)
  double earth_exclusion_rad = 0.3490658504; // [rad] no solution with the boresight this close to the Earth's limb (20°), [0, π)
  std::uint64_t seed = 5;                  // [-] noise seed, any value

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct StarTrackerInput {
  Eigen::Quaterniond q_NB = Eigen::Quaterniond::Identity();  // [-] true attitude, body → inertial
  Eigen::Vector3d w_B_rad_s = Eigen::Vector3d::Zero();       // [rad/s] true body rate
  Eigen::Vector3d sun_B_unit = Eigen::Vector3d::UnitX();     // [-] Sun direction, body axes
  double illumination = 1.0;                                 // [-] 0 in umbra: no Sun to exclude
  Eigen::Vector3d r_N_m = Eigen::Vector3d(7.0e6, 0, 0);      // [m] position, inertial
};

struct StarTrackerOutput {
  Eigen::Quaterniond q_NB_true = Eigen::Quaterniond::Identity();  // [-] the attitude the error acts on
  /// [rad] measurement error as a body-axis rotation: measured = true ⊗ exp(error/2), the
  /// MEKF's own error convention; faults act on it (a bias is a misalignment).
  Eigen::Vector3d error_B_rad = Eigen::Vector3d::Zero();
  bool valid = false;  // rate, Sun and Earth all allow a solution
};

/// Attitude from a star tracker: the true attitude rotated by a small error drawn in the sensor
/// frame (cross-boresight and about-boresight 1σ, the usual datasheet split: Liebe 2002,
/// "Accuracy performance of star trackers—a tutorial", IEEE TAES 38(2), §II), and no solution
/// when the rate smears the stars or the Sun or the lit Earth fills the baffle's exclusion cone.
class StarTrackerModel {
 public:
  using Params = StarTrackerParams;
  using Input = StarTrackerInput;
  using Output = StarTrackerOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit StarTrackerModel(const Params& params);

  /// Replays the noise sequence from the seed.
  void reset();

  /// The sample does not depend on time; t_ns [ns] is kept for the common API.
  Output step(const Input& in, std::int64_t t_ns);

  const Params& params() const { return params_; }

 private:
  Params params_;
  Eigen::Matrix3d R_BS_;
  GaussianNoise noise_;
  std::optional<Eigen::Quaterniond> misalignment_;  // q_BS_true ⊗ q_BS_onboard⁻¹, when they differ
};

/// [-] measured attitude: q ⊗ exp(error/2) (Hamilton, body-axis error).
Eigen::Quaterniond applyError(const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& error_B_rad);

}  // namespace flatsat::star_tracker
