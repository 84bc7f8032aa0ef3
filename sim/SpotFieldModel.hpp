// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "sim/SphericalHarmonicField.hpp"

namespace flatsat::sim {

/// Rotation from the seed's orbit frame O to N, v_N = R_NO * v_O (CNES FR2718105 /
/// CN1148836, Fig. 2, orbit A): X roll, along the orbit opposite to the motion;
/// Z yaw, in the orbit plane pointing away from the Earth's centre; Y pitch = Z × X,
/// opposite to the orbit normal r × v. From the position [m] and velocity [m/s]
/// (not parallel); X is horizontal also on an eccentric orbit.
Eigen::Matrix3d R_NO(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s);

/// [rad] Argument of latitude u in [0, 2π): the angle from the ascending node to r
/// in the direction of motion (the seed's ω0·t). On an equatorial orbit the node is
/// taken along x_N.
double argumentOfLatitude_rad(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s);

/// Geomagnetic field along a near-circular orbit as a short Fourier series in the
/// argument of latitude u, in the orbit frame O (the on-board model of SPOT):
///   b_O(u, r) = (r₀/r)³ Σₖ [cₖ cos(k u) + sₖ sin(k u)],  k = 0..5,
/// the dipole's (r₀/r)³ carrying it over small changes of radius.
class SpotFieldModel {
 public:
  static constexpr int kMaxHarmonic = 5;
  using Harmonics = std::array<Eigen::Vector3d, kMaxHarmonic + 1>;  // [T] in O, index k

  /// @throws std::invalid_argument when the radius is not positive.
  SpotFieldModel(const Harmonics& cos_T, const Harmonics& sin_T, double reference_radius_m);

  /// The seed's first-harmonic model for a polar orbit: Bx = −B0 cos u, By = 0,
  /// Bz = −2 B0 sin u, with B0 = b0_T [T] at reference_radius_m [m].
  static SpotFieldModel firstHarmonic(double b0_T, double reference_radius_m);

  /// The harmonics listed (each in 0..5) of the zonal (m = 0) part of `field` along
  /// a circular orbit of radius orbit_radius_m [m] and inclination_rad [rad]: the
  /// best a function of u alone can follow while the Earth turns beneath the orbit.
  /// {1, 3, 5} is the seed's improved model; {0, …, 5} keeps the even harmonics too.
  /// @throws std::invalid_argument for a harmonic outside 0..5 or a radius ≤ 0.
  static SpotFieldModel zonalHarmonics(const SphericalHarmonicField& field, double orbit_radius_m,
                                       double inclination_rad, const std::vector<int>& harmonics);

  /// [T] Field in O at argument of latitude u [rad] and radius r [m] (> 0).
  Eigen::Vector3d b_O_T(double argument_of_latitude_rad, double radius_m) const;

  const Harmonics& cosineTerms_T() const { return cos_T_; }
  const Harmonics& sineTerms_T() const { return sin_T_; }

 private:
  Harmonics cos_T_;
  Harmonics sin_T_;
  double reference_radius_m_;
};

}  // namespace flatsat::sim
