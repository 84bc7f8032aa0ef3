// SPDX-License-Identifier: Apache-2.0
#include "sim/SphericalHarmonicField.hpp"

#include <cmath>
#include <stdexcept>

#include "sim/Format.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {
namespace {

constexpr int kMaxDegree = GaussCoefficients::kMaxDegree;

}  // namespace

MagneticElements magneticElements(const Eigen::Vector3d& b_G_nT) {
  const double h = std::hypot(b_G_nT.x(), b_G_nT.y());
  return MagneticElements{b_G_nT, h, b_G_nT.norm(), std::atan2(b_G_nT.y(), b_G_nT.x()), std::atan2(b_G_nT.z(), h)};
}

MagneticElementRates magneticElementRates(const Eigen::Vector3d& b_G_nT, const Eigen::Vector3d& b_dot_G_nT_yr) {
  const double x = b_G_nT.x(), y = b_G_nT.y(), z = b_G_nT.z();
  const double xd = b_dot_G_nT_yr.x(), yd = b_dot_G_nT_yr.y(), zd = b_dot_G_nT_yr.z();
  const double h = std::hypot(x, y);
  const double f = b_G_nT.norm();
  const double h_dot = (x * xd + y * yd) / h;
  return MagneticElementRates{b_dot_G_nT_yr, h_dot, (x * xd + y * yd + z * zd) / f, (x * yd - y * xd) / (h * h),
                              (h * zd - z * h_dot) / (f * f)};
}

SphericalHarmonicField::SphericalHarmonicField(const GaussCoefficients& coefficients, double reference_radius_m)
    : coefficients_(coefficients), reference_radius_m_(reference_radius_m) {
  if (coefficients.degree < 1 || coefficients.degree > kMaxDegree) {
    throw std::invalid_argument("SphericalHarmonicField: degree " + std::to_string(coefficients.degree) +
                                " is outside 1..13");
  }
  if (!(reference_radius_m > 0.0)) {
    throw std::invalid_argument("SphericalHarmonicField: reference radius " + formatNumber(reference_radius_m) +
                                " m must be positive");
  }
  for (int n = 1; n <= kMaxDegree; ++n) {
    zonal_slope_[n] = std::sqrt(0.5 * n * (n + 1));
    if (n >= 2) sectoral_[n] = std::sqrt(1.0 - 0.5 / n);
    for (int m = 0; m <= n; ++m) {
      root_n2_m2_[n][m] = std::sqrt(double(n * n - m * m));
      if (m == n) continue;
      recursion_a_[n][m] = (2.0 * n - 1.0) / root_n2_m2_[n][m];
      recursion_b_[n][m] = std::sqrt(double((n - 1) * (n - 1) - m * m)) / root_n2_m2_[n][m];
    }
  }
}

SphericalHarmonicField::Direction SphericalHarmonicField::direction(const GeocentricPosition& p) {
  return {p.radius_m, std::sin(p.latitude_rad), std::cos(p.latitude_rad), std::sin(p.longitude_rad),
          std::cos(p.longitude_rad)};
}

Eigen::Vector3d SphericalHarmonicField::synthesize(const Table& g, const Table& h, const Direction& p) const {
  // Potential V = a Σₙ (a/r)^(n+1) Σₘ [gₙᵐ cos mλ + hₙᵐ sin mλ] Pₙᵐ(cos θ), θ the
  // geocentric colatitude, and B = −∇V (Alken et al. 2021, Eq. 1). In geocentric NED:
  //   X′ =  Σₙ (a/r)^(n+2) Σₘ (g cos mλ + h sin mλ) dPₙᵐ/dθ
  //   Y′ =  Σₙ (a/r)^(n+2) Σₘ m (g sin mλ − h cos mλ) Pₙᵐ / sin θ
  //   Z′ = −Σₙ (n+1) (a/r)^(n+2) Σₘ (g cos mλ + h sin mλ) Pₙᵐ
  // Pₙᵐ are Schmidt semi-normalised: √((2 − δₘ₀)(n−m)!/(n+m)!) times the Ferrers
  // functions. For m ≥ 1 they carry a factor sin θ, so the recursions run on
  // Qₙᵐ = Pₙᵐ / sin θ, which is finite at the poles: Y′ and dPₙᵐ/dθ need no division
  // by sin θ, and the east component and D keep their limits on the polar axis, the
  // meridian being the one of the longitude given (what the WMM's special pole
  // summation computes).
  const int degree = coefficients_.degree;
  const double mu = p.sin_lat;     // cos θ
  const double sin_t = p.cos_lat;  // sin θ ≥ 0

  std::array<double, kMaxDegree + 1> cos_ml;
  std::array<double, kMaxDegree + 1> sin_ml;
  cos_ml[0] = 1.0;
  sin_ml[0] = 0.0;
  cos_ml[1] = p.cos_lon;
  sin_ml[1] = p.sin_lon;
  for (int m = 2; m <= degree; ++m) {
    cos_ml[m] = cos_ml[m - 1] * cos_ml[1] - sin_ml[m - 1] * sin_ml[1];
    sin_ml[m] = sin_ml[m - 1] * cos_ml[1] + cos_ml[m - 1] * sin_ml[1];
  }

  // Degree recursion (Abramowitz & Stegun 8.5.3, Schmidt-normalised):
  //   √(n² − m²) Pₙᵐ = (2n − 1) cos θ Pₙ₋₁ᵐ − √((n−1)² − m²) Pₙ₋₂ᵐ,
  // started from P₀⁰ = 1 and the sectoral Qₘᵐ = √(1 − 1/(2m)) sin θ Qₘ₋₁ᵐ⁻¹, Q₁¹ = 1.
  // The recursions run degree by degree, every order of a degree from the two
  // degrees before: the orders are independent of each other, so the
  // processor overlaps them (order by order, each was a chain of dependent
  // multiplications, and the synthesis waited on it). Each Qₙᵐ is
  // summed into the field as it is made, and what every order of a degree
  // shares (n cos θ, sin θ in Z′) is taken out of the sums.
  std::array<double, kMaxDegree + 1> p0;  // Pₙ⁰
  Table q;                                // q[n][m] = Qₙᵐ, m ≥ 1, n ≥ m − 1
  p0[0] = 1.0;
  p0[1] = mu;
  q[0][1] = 0.0;
  q[1][1] = 1.0;
  const double ratio = reference_radius_m_ / p.radius_m;
  double radial = ratio * ratio;  // (a/r)^(n+2) after the first multiplication
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int n = 1; n <= degree; ++n) {
    if (n >= 2) {
      p0[n] = recursion_a_[n][0] * mu * p0[n - 1] - recursion_b_[n][0] * p0[n - 2];
      q[n - 1][n] = 0.0;
      q[n][n] = sectoral_[n] * sin_t * q[n - 1][n - 1];
    }
    radial *= ratio;
    const double n_mu = n * mu;
    double x = 0.0;
    double y = 0.0;
    double z = 0.0;  // Σₘ (g cos mλ + h sin mλ) Qₙᵐ, times sin θ below
    double order = 1.0;
    for (int m = 1; m <= n; ++m, order += 1.0) {
      if (m < n) q[n][m] = recursion_a_[n][m] * mu * q[n - 1][m] - recursion_b_[n][m] * q[n - 2][m];
      const double gh_cos = g[n][m] * cos_ml[m] + h[n][m] * sin_ml[m];
      const double gh_sin = g[n][m] * sin_ml[m] - h[n][m] * cos_ml[m];
      // sin θ dPₙᵐ/dθ = n cos θ Pₙᵐ − √(n² − m²) Pₙ₋₁ᵐ (A&S 8.5.4, Schmidt-normalised).
      const double dp = n_mu * q[n][m] - root_n2_m2_[n][m] * q[n - 1][m];
      x += gh_cos * dp;
      y += order * gh_sin * q[n][m];
      z += gh_cos * q[n][m];
    }
    // dPₙ⁰/dθ = −√(n(n+1)/2) Pₙ¹ (A&S 8.5.4 at m = 0 with the Schmidt factors).
    x -= g[n][0] * zonal_slope_[n] * sin_t * q[n][1];
    z = g[n][0] * p0[n] + sin_t * z;
    b += radial * Eigen::Vector3d(x, y, -(n + 1) * z);
  }
  return b;
}

Eigen::Vector3d SphericalHarmonicField::b_C_nT(const GeocentricPosition& p) const {
  return synthesize(coefficients_.g_nT, coefficients_.h_nT, direction(p));
}

Eigen::Vector3d SphericalHarmonicField::bDot_C_nT_yr(const GeocentricPosition& p) const {
  return synthesize(coefficients_.g_dot_nT_yr, coefficients_.h_dot_nT_yr, direction(p));
}

Eigen::Vector3d SphericalHarmonicField::b_G_nT(const GeodeticPosition& p) const {
  const GeocentricPosition c = geocentricFromGeodetic(p);
  return R_GC(p.latitude_rad, c.latitude_rad) * b_C_nT(c);
}

Eigen::Vector3d SphericalHarmonicField::bDot_G_nT_yr(const GeodeticPosition& p) const {
  const GeocentricPosition c = geocentricFromGeodetic(p);
  return R_GC(p.latitude_rad, c.latitude_rad) * bDot_C_nT_yr(c);
}

MagneticElements SphericalHarmonicField::elements(const GeodeticPosition& p) const {
  return magneticElements(b_G_nT(p));
}

Eigen::Vector3d SphericalHarmonicField::b_E_T(const Eigen::Vector3d& r_E_m) const {
  // The geocentric point of geocentricFromEarthFixed() (longitude 0 on the
  // polar axis) and R_EC() at it, from the coordinates' ratios.
  const double rho = std::hypot(r_E_m.x(), r_E_m.y());
  const double r = r_E_m.norm();
  const Direction d{r, r_E_m.z() / r, rho / r, rho > 0.0 ? r_E_m.y() / rho : 0.0,
                    rho > 0.0 ? r_E_m.x() / rho : 1.0};
  const Eigen::Vector3d b_C = synthesize(coefficients_.g_nT, coefficients_.h_nT, d);
  const double along_rho = -d.sin_lat * b_C.x() - d.cos_lat * b_C.z();  // N and D on the outward equatorial direction
  return 1e-9 * Eigen::Vector3d(d.cos_lon * along_rho - d.sin_lon * b_C.y(),
                                d.sin_lon * along_rho + d.cos_lon * b_C.y(),
                                d.cos_lat * b_C.x() - d.sin_lat * b_C.z());
}

Eigen::Vector3d SphericalHarmonicField::b_N_T(const Eigen::Vector3d& r_N_m, double jd_ut1) const {
  const Eigen::Matrix3d R = R_EN(jd_ut1);
  return R.transpose() * b_E_T(R * r_N_m);
}

SphericalHarmonicField igrf14(const std::string& igrf_coeff_file, double decimal_year) {
  return SphericalHarmonicField(igrf14Coefficients(igrf_coeff_file, decimal_year));
}

SphericalHarmonicField wmm2025(const std::string& wmm_cof_file, double decimal_year) {
  return SphericalHarmonicField(wmm2025Coefficients(wmm_cof_file, decimal_year));
}

}  // namespace flatsat::sim
