// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "components/common/GaussianNoise.hpp"
#include "sim/Albedo.hpp"

namespace flatsat::sun_sensor {

inline constexpr int kMaxSunCells = 12;

enum class SunSensorKind {
  kFineTwoAxis,   // two transverse angles of a slit or quadrant head, inside its field of view
  kCoarseCosine,  // an array of photocells, each giving the cosine of the Sun's incidence
};

/// Fine two-axis sun sensor, or a coarse cosine array.
struct SunSensorParams {
  Eigen::Vector3d boresight_B = Eigen::Vector3d::UnitX();  // [-] boresight in body axes, unit length
  double noise_rad = 1.0e-4;                               // [rad] 1σ noise of each transverse angle, >= 0
  double fov_half_angle_rad = 1.0471975511965976;          // [rad] cone half-angle (60°), (0, π/2)
  double min_illumination = 0.5;                           // [-] below this Sun fraction: no Sun, [0, 1]
  std::uint64_t seed = 2;                                  // [-] noise seed, any value
  SunSensorKind kind = SunSensorKind::kFineTwoAxis;
  // Coarse cosine array only:
  /// [-] unit cell normals in body axes, in opposite pairs (the usual six cube faces), 2..12
  std::vector<Eigen::Vector3d> cell_normals_B = {Eigen::Vector3d::UnitX(),  -Eigen::Vector3d::UnitX(),
                                                 Eigen::Vector3d::UnitY(),  -Eigen::Vector3d::UnitY(),
                                                 Eigen::Vector3d::UnitZ(),  -Eigen::Vector3d::UnitZ()};
  double cell_noise = 0.005;  // [-] 1σ of each cell's output; 1 = the Sun at normal incidence at 1 AU, >= 0
  double min_output = 0.5;    // [-] estimated Sun strength below this: no Sun (eclipse, albedo alone), > 0
  std::optional<sim::AlbedoParams> albedo;  // [-] Earth albedo on the cells; nullopt: none
  /// [-] unit; the boresight flight software converts the angles with (the vehicle's onboard
  /// mounting); nullopt: boresight_B. A fine sensor's measured direction is turned by the
  /// rotation that takes boresight_B onto it (a mounting known wrongly).
  std::optional<Eigen::Vector3d> boresight_onboard_B;

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct SunSensorInput {
  Eigen::Vector3d sun_B_unit = Eigen::Vector3d::UnitX();  // [-] true Sun direction in body axes
  double illumination = 1.0;                              // [-] visible fraction of the solar disc, 0 = umbra
  double flux_ratio = 1.0;     // [-] solar flux at the spacecraft / at 1 AU, shadow included (coarse)
  Eigen::Vector3d r_B_m = Eigen::Vector3d::Zero();  // [m] position from the Earth's centre, body axes (albedo)
};

struct SunSensorOutput {
  Eigen::Vector3d sun_B_unit = Eigen::Vector3d::Zero();  // [-] measured Sun direction; zero when !valid
  bool valid = false;                                    // Sun lit enough and inside the field of view
  std::array<double, kMaxSunCells> cell_output{};        // [-] coarse: each cell's output (1: normal Sun at 1 AU)
  int cell_count = 0;                                    // [-] coarse: live entries of cell_output
};

/// Fine: measures the two angles of the Sun from the boresight, α = atan2(s·t1, s·b) and
/// β = atan2(s·t2, s·b) with t1, t2 the transverse axes, adds independent noise to each
/// and rebuilds the unit vector from their tangents, the quantities a two-axis slit or
/// quadrant sensor resolves (Wertz (ed.), Spacecraft Attitude Determination and Control,
/// 1978, §7.1 Sun sensor models).
/// Coarse: cell i gives y_i = f max(0, n_i·s) + E_alb,i/E☉ + noise (Wertz §7.1.1, cosine
/// detectors; f the flux ratio, E_alb from sim::albedoIrradiance). With cells in opposite
/// pairs, Nᵀy = f (Σ_pairs n nᵀ) s = ½ f NᵀN s, so the least-squares ŝ = (NᵀN)⁻¹Nᵀy is f s/2
/// exactly without noise and albedo: its direction is the Sun's, twice its size the Sun's
/// strength, which must reach min_output. Albedo biases it toward the lit Earth, as it does
/// on orbit.
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
  Output coarse(const Input& in);

  Params params_;
  Eigen::MatrixXd cell_pinv_;  // (NᵀN)⁻¹Nᵀ of the coarse cells
  Eigen::Vector3d t1_B_;
  Eigen::Vector3d t2_B_;
  double cos_fov_;
  GaussianNoise noise_;
  std::optional<Eigen::Quaterniond> misknown_mounting_;  // boresight_B onto boresight_onboard_B, when they differ
};

}  // namespace flatsat::sun_sensor
