// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <Eigen/Core>

namespace flatsat::sim {

/// Earth albedo on a flat plate: the Earth as a sphere that reflects sunlight diffusely
/// (Lambert) with a uniform Bond albedo. Each surface element of the cap the spacecraft
/// sees, lit by the Sun at incidence θs, has radiance L = a E☉ cos θs / π; the plate of
/// normal n at r receives ∫ L cos θe cos θp / d² dA over that cap (θe: emission angle at
/// the element, θp: incidence on the plate, d: their distance), here by a midpoint rule in
/// the angle from the sub-satellite point and its azimuth. Far from the Earth this tends to
/// Russell's (1916) law for a Lambert sphere, E = (2/3) a E☉ (R/r)² Φ(α) with
/// Φ(α) = (sin α + (π − α) cos α)/π and α the Sun–Earth–spacecraft phase angle.
/// Any frame will do: r, the Sun direction and n in the same axes.
struct AlbedoParams {
  double albedo = 0.3;         // [-] Bond albedo, [0, 1] (0.3: the Earth's mean, e.g. CERES)
  int rings = 48;              // [-] quadrature rings from the sub-satellite point to the horizon, >= 4
  int sectors = 96;            // [-] azimuth sectors per ring, >= 8
};

/// [-] Irradiance on the plate in units of the solar irradiance E☉ at the spacecraft
/// (multiply by the solar flux): 0 when the plate faces away from the Earth or the cap is dark.
/// @param r_m [m] spacecraft position from the Earth's centre, |r| > R_E
/// @param sun_unit [-] direction to the Sun (the Sun is far: the same over the cap)
/// @param normal_unit [-] plate normal
double albedoIrradiance(const Eigen::Vector3d& r_m, const Eigen::Vector3d& sun_unit, const Eigen::Vector3d& normal_unit,
                        const AlbedoParams& params);

/// [-] Russell's far-field law above, for the plate facing the Earth's centre.
double lambertSphereFarField(double distance_m, double phase_angle_rad, double albedo);

}  // namespace flatsat::sim
