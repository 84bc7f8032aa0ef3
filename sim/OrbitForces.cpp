// SPDX-License-Identifier: Apache-2.0
#include "sim/OrbitForces.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "sim/Format.hpp"
#include "sim/MoonEphemeris.hpp"
#include "sim/SunEphemeris.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {
namespace {

// J_n by degree n (degrees 0 and 1 vanish about the centre of mass).
constexpr double kZonalJ[5] = {0.0, 0.0, kEgm2008J2, kEgm2008J3, kEgm2008J4};

void checkRange(double value, double lo, double hi, const std::string& field, std::vector<std::string>& errors) {
  if (!(value >= lo && value <= hi)) {
    errors.push_back(field + ": " + formatNumber(value) + " must be in [" + formatNumber(lo) + ", " + formatNumber(hi) +
                     "]");
  }
}

const OrbitForceParams& validated(const OrbitForceParams& params) {
  const std::vector<std::string> errors = params.validate();
  if (!errors.empty()) {
    std::string message = "invalid OrbitForceParams: " + errors.front();
    for (std::size_t i = 1; i < errors.size(); ++i) message += "; " + errors[i];
    throw std::invalid_argument(message);
  }
  return params;
}

}  // namespace

std::vector<std::string> OrbitForceParams::validate() const {
  std::vector<std::string> errors;
  if (!(std::isfinite(mass_kg) && mass_kg > 0.0)) {
    errors.push_back("mass_kg: " + formatNumber(mass_kg) + " kg must be finite and > 0");
  }
  checkRange(drag_area_m2, 0.0, 1e4, "drag_area_m2", errors);
  checkRange(drag_coefficient, 0.0, 5.0, "drag_coefficient", errors);
  checkRange(srp_area_m2, 0.0, 1e4, "srp_area_m2", errors);
  checkRange(reflectivity_coefficient, 1.0, 2.0, "reflectivity_coefficient", errors);
  checkRange(tt_minus_utc_s, 32.184, 120.0, "tt_minus_utc_s", errors);
  for (const std::string& error : atmosphere.validate()) errors.push_back("atmosphere." + error);
  return errors;
}

Eigen::Vector3d pointMassAcceleration_N(const Eigen::Vector3d& r_N_m, double mu_m3_s2) {
  const double r2 = r_N_m.squaredNorm();
  return (-mu_m3_s2 / (r2 * std::sqrt(r2))) * r_N_m;
}

Eigen::Vector3d zonalAcceleration_N(const Eigen::Vector3d& r_N_m, bool j2, bool j3, bool j4) {
  const double r = r_N_m.norm();
  const double s = r_N_m.z() / r;
  const double ratio = kEgm2008Radius_m / r;
  // Legendre polynomials by Bonnet's recursion (k+1) P_(k+1) = (2k+1) s P_k − k P_(k−1)
  // and their derivatives by P'_(k+1) = (k+1) P_k + s P'_k; one pass serves every degree.
  const bool enabled[5] = {false, false, j2, j3, j4};
  double p_prev = 1.0;   // P_(k−1)
  double p = s;          // P_k
  double dp = 1.0;       // P'_k
  double power = ratio;  // (R/r)^k
  double radial = 0.0;   // Σ J_n (R/r)ⁿ P'_(n+1)
  double axial = 0.0;    // Σ J_n (R/r)ⁿ P'_n
  for (int k = 1; k <= 4; ++k) {
    const double dp_next = (k + 1) * p + s * dp;
    if (enabled[k]) {
      radial += kZonalJ[k] * power * dp_next;
      axial += kZonalJ[k] * power * dp;
    }
    const double p_next = ((2 * k + 1) * s * p - k * p_prev) / (k + 1);
    p_prev = p;
    p = p_next;
    dp = dp_next;
    power *= ratio;
  }
  const double scale = kMuEarth_m3_s2 / (r * r);
  return scale * (radial / r * r_N_m - axial * Eigen::Vector3d::UnitZ());
}

Eigen::Vector3d sectoralJ22Acceleration_N(const Eigen::Vector3d& r_N_m, double earth_angle_rad) {
  const double c = std::cos(earth_angle_rad), s = std::sin(earth_angle_rad);
  const double x = c * r_N_m.x() + s * r_N_m.y(), y = -s * r_N_m.x() + c * r_N_m.y(), z = r_N_m.z();
  const double r2 = r_N_m.squaredNorm(), r5 = r2 * r2 * std::sqrt(r2);
  const double k = 3.0 * kMuEarth_m3_s2 * kEgm2008Radius_m * kEgm2008Radius_m;
  const double u = kEgm2008C22 * (x * x - y * y) + 2.0 * kEgm2008S22 * x * y;  // U = k u / r⁵
  const double radial = -5.0 * k * u / (r5 * r2);                              // ∂(r⁻⁵)/∂x_j = −5 x_j / r⁷
  const Eigen::Vector3d a_E(k * 2.0 * (kEgm2008C22 * x + kEgm2008S22 * y) / r5 + radial * x,
                            k * 2.0 * (-kEgm2008C22 * y + kEgm2008S22 * x) / r5 + radial * y, radial * z);
  return {c * a_E.x() - s * a_E.y(), s * a_E.x() + c * a_E.y(), a_E.z()};
}

Eigen::Vector3d dragAcceleration_N(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s, double density_kg_m3,
                                   double ballistic_m2_kg) {
  const Eigen::Vector3d v_rel = velocityThroughAir_N_m_s(r_N_m, v_N_m_s);
  return (-0.5 * density_kg_m3 * ballistic_m2_kg * v_rel.norm()) * v_rel;
}

Eigen::Vector3d solarPressureAcceleration_N(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& sun_N_m,
                                            double cr_area_over_mass_m2_kg) {
  const Eigen::Vector3d to_sun = sun_N_m - r_N_m;
  const double d2 = to_sun.squaredNorm();
  // On the day side (Earth centre ≥ 90° from the Sun, seen from the satellite) the
  // disks cannot touch while the Earth's apparent radius b and the Sun's a satisfy
  // a + b ≤ 90°, i.e. |r|² cos²a ≥ R²: full Sun without the shadow geometry's arcsines.
  const bool day_side = r_N_m.dot(to_sun) >= 0.0 && r_N_m.squaredNorm() * (1.0 - kSunRadius_m * kSunRadius_m / d2) >=
                                                        kEarthEquatorialRadius_m * kEarthEquatorialRadius_m;
  const double nu = day_side ? 1.0 : illumination(r_N_m, sun_N_m);
  if (nu == 0.0) return Eigen::Vector3d::Zero();
  const double scale = nu * kSolarPressure1Au_N_m2 * cr_area_over_mass_m2_kg * kAstronomicalUnit_m *
                       kAstronomicalUnit_m / (d2 * std::sqrt(d2));
  return -scale * to_sun;
}

Eigen::Vector3d thirdBodyAcceleration_N(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& body_N_m,
                                        double mu_m3_s2) {
  const Eigen::Vector3d to_body = body_N_m - r_N_m;
  const double d = to_body.norm();
  const double s = body_N_m.norm();
  return mu_m3_s2 * (to_body / (d * d * d) - body_N_m / (s * s * s));
}

OrbitForces::OrbitForces(const OrbitForceParams& params)
    : params_(validated(params)),
      atmosphere_(params.atmosphere),
      ballistic_m2_kg_(params.drag_coefficient * params.drag_area_m2 / params.mass_kg),
      cr_area_over_mass_m2_kg_(params.reflectivity_coefficient * params.srp_area_m2 / params.mass_kg) {}

Ephemerides OrbitForces::ephemeridesAt(double jd_tt) const {
  Ephemerides bodies;
  // The Harris–Priester bulge follows the Sun too.
  const bool bulge = params_.drag && params_.atmosphere.model == DensityModel::kHarrisPriester;
  if (params_.sun_gravity || params_.solar_pressure || bulge) bodies.sun_N_m = sunPosition_N_m(jd_tt);
  if (params_.moon_gravity) bodies.moon_N_m = moonPosition_N_m(jd_tt);
  if (params_.j22) bodies.earth_angle_rad = gmst_rad(jd_tt - params_.tt_minus_utc_s / kSecondsPerDay);
  return bodies;
}

Eigen::Vector3d OrbitForces::acceleration_N(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s,
                                            const Ephemerides& bodies) const {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  if (params_.central_gravity) a += pointMassAcceleration_N(r_N_m, kMuEarth_m3_s2);
  if (params_.j2 || params_.j3 || params_.j4) a += zonalAcceleration_N(r_N_m, params_.j2, params_.j3, params_.j4);
  if (params_.j22) a += sectoralJ22Acceleration_N(r_N_m, bodies.earth_angle_rad);
  if (params_.drag) {
    const double density = atmosphere_.density_kg_m3(r_N_m, bodies.sun_N_m.normalized());
    a += dragAcceleration_N(r_N_m, v_N_m_s, density, ballistic_m2_kg_);
  }
  if (params_.solar_pressure) a += solarPressureAcceleration_N(r_N_m, bodies.sun_N_m, cr_area_over_mass_m2_kg_);
  if (params_.sun_gravity) a += thirdBodyAcceleration_N(r_N_m, bodies.sun_N_m, kMuSun_m3_s2);
  if (params_.moon_gravity) a += thirdBodyAcceleration_N(r_N_m, bodies.moon_N_m, kMuMoon_m3_s2);
  return a;
}

}  // namespace flatsat::sim
