// SPDX-License-Identifier: Apache-2.0
#include "sim/KeplerOrbit.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "sim/Constants.hpp"
#include "sim/Format.hpp"

namespace flatsat::sim {
std::vector<std::string> OrbitElements::validate() const {
  std::vector<std::string> errors;
  if (!std::isfinite(semi_major_axis_m) || semi_major_axis_m <= kEarthEquatorialRadius_m) {
    errors.push_back("semi_major_axis_m: " + formatNumber(semi_major_axis_m) +
                     " m must be above the Earth's equatorial radius (" + formatNumber(kEarthEquatorialRadius_m) +
                     " m)");
  }
  if (!(eccentricity >= 0.0 && eccentricity < 1.0)) {
    errors.push_back("eccentricity: " + formatNumber(eccentricity) + " must be in [0, 1)");
  } else if (std::isfinite(semi_major_axis_m) && semi_major_axis_m > kEarthEquatorialRadius_m &&
             semi_major_axis_m * (1.0 - eccentricity) <= kEarthEquatorialRadius_m) {
    errors.push_back("eccentricity: perigee radius a(1 − e) = " +
                     formatNumber(semi_major_axis_m * (1.0 - eccentricity)) + " m is inside the Earth");
  }
  if (!(inclination_rad >= 0.0 && inclination_rad <= kPi)) {
    errors.push_back("inclination_rad: " + formatNumber(inclination_rad) + " must be in [0, π]");
  }
  if (!std::isfinite(raan_rad)) errors.push_back("raan_rad: must be finite");
  if (!std::isfinite(arg_perigee_rad)) errors.push_back("arg_perigee_rad: must be finite");
  if (!std::isfinite(mean_anomaly_rad)) errors.push_back("mean_anomaly_rad: must be finite");
  return errors;
}

double solveKepler(double mean_anomaly, double e) {
  // Solve for the anomaly reduced to [−π, π) and add the whole revolutions back,
  // so that Newton always starts from Vallado's guess E₀ = M ± e, which
  // converges for every e < 1.
  const double revolutions = std::floor((mean_anomaly + kPi) / (2.0 * kPi));
  const double m = mean_anomaly - 2.0 * kPi * revolutions;
  double ecc_anomaly = m < 0.0 ? m - e : m + e;
  for (int i = 0; i < 50; ++i) {
    const double step = (ecc_anomaly - e * std::sin(ecc_anomaly) - m) / (1.0 - e * std::cos(ecc_anomaly));
    ecc_anomaly -= step;
    if (std::abs(step) < 1e-14) break;
  }
  return ecc_anomaly + 2.0 * kPi * revolutions;
}

KeplerOrbit::KeplerOrbit(const OrbitElements& elements, double mu)
    : elements_(elements),
      mu_(mu),
      mean_motion_rad_s_(std::sqrt(mu / std::pow(elements.semi_major_axis_m, 3))),
      // Vallado Alg. 10 (COE2RV): R_NP = R3(−Ω) R1(−i) R3(−ω).
      R_NP_((Eigen::AngleAxisd(elements.raan_rad, Eigen::Vector3d::UnitZ()) *
             Eigen::AngleAxisd(elements.inclination_rad, Eigen::Vector3d::UnitX()) *
             Eigen::AngleAxisd(elements.arg_perigee_rad, Eigen::Vector3d::UnitZ()))
                .toRotationMatrix()) {}

KeplerOrbit::State KeplerOrbit::at(double t_s) const {
  const double e = elements_.eccentricity;
  const double ecc_anomaly = solveKepler(elements_.mean_anomaly_rad + mean_motion_rad_s_ * t_s, e);
  // True anomaly by the half-angle identity tan(ν/2) = √((1+e)/(1−e)) tan(E/2),
  // in atan2 form so that it holds in every quadrant.
  const double nu = 2.0 * std::atan2(std::sqrt(1.0 + e) * std::sin(0.5 * ecc_anomaly),
                                     std::sqrt(1.0 - e) * std::cos(0.5 * ecc_anomaly));
  // Vallado Alg. 10 (COE2RV): perifocal position and velocity from p and ν.
  const double p = elements_.semi_major_axis_m * (1.0 - e * e);
  const double r = p / (1.0 + e * std::cos(nu));
  const double v_scale = std::sqrt(mu_ / p);
  const Eigen::Vector3d r_P(r * std::cos(nu), r * std::sin(nu), 0.0);
  const Eigen::Vector3d v_P(-v_scale * std::sin(nu), v_scale * (e + std::cos(nu)), 0.0);
  return State{R_NP_ * r_P, R_NP_ * v_P};
}

double KeplerOrbit::period_s() const { return 2.0 * kPi / mean_motion_rad_s_; }

double KeplerOrbit::meanMotion_rad_s() const { return mean_motion_rad_s_; }

}  // namespace flatsat::sim
