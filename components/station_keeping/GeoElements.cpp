// SPDX-License-Identifier: Apache-2.0
#include "components/station_keeping/GeoElements.hpp"

#include <cmath>
#include <numbers>

#include "sim/Constants.hpp"

namespace flatsat::station_keeping {

namespace {

double wrapPi(double angle_rad) { return std::remainder(angle_rad, 2.0 * std::numbers::pi); }

}  // namespace

SynchronousElements synchronousElements(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s,
                                        double gmst_rad) {
  const double mu = sim::kMuEarth_m3_s2;
  const double r = r_N_m.norm(), v2 = v_N_m_s.squaredNorm();
  SynchronousElements out;
  out.semi_major_axis_m = 1.0 / (2.0 / r - v2 / mu);
  out.drift_rad_s = std::sqrt(mu / std::pow(out.semi_major_axis_m, 3)) - sim::kEarthRotationRate_rad_s;

  const Eigen::Vector3d w = r_N_m.cross(v_N_m_s).normalized();  // orbit normal (sin i sin Ω, −sin i cos Ω, cos i)
  const double sin_i = std::hypot(w.x(), w.y());
  const double inclination = std::atan2(sin_i, w.z());
  out.i = (sin_i > 1e-15 ? inclination / sin_i : 1.0) * Eigen::Vector2d(w.x(), w.y());

  // Equinoctial frame: p = tan(i/2) sin Ω, q = tan(i/2) cos Ω (Broucke & Cefola).
  const double p = w.x() / (1.0 + w.z()), q = -w.y() / (1.0 + w.z());
  const double k = 1.0 + p * p + q * q;
  const Eigen::Vector3d f = Eigen::Vector3d(1.0 - p * p + q * q, 2.0 * p * q, -2.0 * p) / k;
  const Eigen::Vector3d g = Eigen::Vector3d(2.0 * p * q, 1.0 + p * p - q * q, 2.0 * q) / k;
  const Eigen::Vector3d e_N = ((v2 - mu / r) * r_N_m - r_N_m.dot(v_N_m_s) * v_N_m_s) / mu;
  out.e = {e_N.dot(f), e_N.dot(g)};

  // Mean longitude l = ϖ + M from the true longitude L = ϖ + ν.
  const double e = out.e.norm();
  const double true_longitude = std::atan2(r_N_m.dot(g), r_N_m.dot(f));
  const double perigee = std::atan2(out.e.y(), out.e.x());
  const double nu = true_longitude - perigee;
  const double E = 2.0 * std::atan(std::sqrt((1.0 - e) / (1.0 + e)) * std::tan(0.5 * nu));
  const double M = E - e * std::sin(E);
  out.longitude_rad = wrapPi(perigee + M - gmst_rad);
  return out;
}

ImpulseEffect impulseEffect(const Eigen::Vector3d& dv_orbital_m_s, double ra_rad, double v_m_s, double n_rad_s) {
  const double s = std::sin(ra_rad), c = std::cos(ra_rad);
  const double tangential = dv_orbital_m_s.x() / v_m_s, normal = dv_orbital_m_s.y() / v_m_s,
               radial = dv_orbital_m_s.z() / v_m_s;
  ImpulseEffect effect;
  effect.i = normal * Eigen::Vector2d(s, -c);
  effect.e = radial * Eigen::Vector2d(s, -c) + 2.0 * tangential * Eigen::Vector2d(c, s);
  effect.drift_rad_s = -3.0 * n_rad_s * tangential;
  effect.longitude_rad = -2.0 * radial;
  return effect;
}

}  // namespace flatsat::station_keeping
