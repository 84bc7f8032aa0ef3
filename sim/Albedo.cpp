// SPDX-License-Identifier: Apache-2.0
#include "sim/Albedo.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "sim/Constants.hpp"

namespace flatsat::sim {

double albedoIrradiance(const Eigen::Vector3d& r_m, const Eigen::Vector3d& sun_unit, const Eigen::Vector3d& normal_unit,
                        const AlbedoParams& params) {
  const double R = kEarthEquatorialRadius_m;
  const double r = r_m.norm();
  if (!(r > R) || params.albedo <= 0.0) return 0.0;
  const Eigen::Vector3d up = r_m / r;
  const Eigen::Vector3d e1 = up.unitOrthogonal();
  const Eigen::Vector3d e2 = up.cross(e1);
  const double horizon = std::acos(R / r);  // angular radius of the visible cap
  const double du = horizon / params.rings;
  const double dphi = 2.0 * std::numbers::pi / params.sectors;
  double sum = 0.0;
  for (int i = 0; i < params.rings; ++i) {
    const double u = (i + 0.5) * du;
    const double area = R * R * std::sin(u) * du * dphi;
    for (int j = 0; j < params.sectors; ++j) {
      const double phi = (j + 0.5) * dphi;
      const Eigen::Vector3d n_p = std::cos(u) * up + std::sin(u) * (std::cos(phi) * e1 + std::sin(phi) * e2);
      const double cos_sun = n_p.dot(sun_unit);
      if (cos_sun <= 0.0) continue;  // night side
      const Eigen::Vector3d d = r_m - R * n_p;  // element → spacecraft
      const double d2 = d.squaredNorm();
      const Eigen::Vector3d d_unit = d / std::sqrt(d2);
      const double cos_emit = n_p.dot(d_unit);
      const double cos_plate = -normal_unit.dot(d_unit);
      if (cos_emit <= 0.0 || cos_plate <= 0.0) continue;
      sum += cos_sun * cos_emit * cos_plate / d2 * area;
    }
  }
  return params.albedo / std::numbers::pi * sum;
}

double lambertSphereFarField(double distance_m, double phase_angle_rad, double albedo) {
  const double a = std::clamp(phase_angle_rad, 0.0, std::numbers::pi);
  const double phase = (std::sin(a) + (std::numbers::pi - a) * std::cos(a)) / std::numbers::pi;
  const double ratio = kEarthEquatorialRadius_m / distance_m;
  return 2.0 / 3.0 * albedo * ratio * ratio * phase;
}

}  // namespace flatsat::sim
