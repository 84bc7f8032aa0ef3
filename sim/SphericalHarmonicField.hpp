// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "sim/Constants.hpp"
#include "sim/GeomagneticCoefficients.hpp"
#include "sim/Geodetic.hpp"

namespace flatsat::sim {

/// Field elements at a point, as the public geomagnetic calculators give them.
struct MagneticElements {
  Eigen::Vector3d b_G_nT;        // [nT] (X north, Y east, Z down) in the geodetic NED frame G
  double h_nT = 0.0;             // [nT] horizontal intensity H
  double f_nT = 0.0;             // [nT] total intensity F
  double declination_rad = 0.0;  // [rad] D, east of true north, (−π, π]
  double inclination_rad = 0.0;  // [rad] I, down from horizontal, [−π/2, π/2]
};

/// H, F, D, I of b_G_nT [nT] (WMM2025 Technical Report, §1.2).
MagneticElements magneticElements(const Eigen::Vector3d& b_G_nT);

/// Yearly rates of the field elements.
struct MagneticElementRates {
  Eigen::Vector3d b_dot_G_nT_yr;        // [nT/yr] (Ẋ, Ẏ, Ż)
  double h_dot_nT_yr = 0.0;             // [nT/yr] Ḣ
  double f_dot_nT_yr = 0.0;             // [nT/yr] Ḟ
  double declination_dot_rad_yr = 0.0;  // [rad/yr] Ḋ
  double inclination_dot_rad_yr = 0.0;  // [rad/yr] İ
};

/// Rates from the field [nT] (H > 0) and its secular variation [nT/yr], by
/// differentiating the element formulas: Ḣ = (XẊ + YẎ)/H, Ḟ = (XẊ + YẎ + ZŻ)/F,
/// Ḋ = (XẎ − YẊ)/H², İ = (HŻ − ZḢ)/F².
MagneticElementRates magneticElementRates(const Eigen::Vector3d& b_G_nT, const Eigen::Vector3d& b_dot_G_nT_yr);

/// Internal geomagnetic field of degree N ≤ 13 from Gauss coefficients (IGRF, WMM).
/// Evaluation allocates nothing and never throws.
class SphericalHarmonicField {
 public:
  /// @throws std::invalid_argument when the degree is outside 1..13 or the radius is not positive.
  explicit SphericalHarmonicField(const GaussCoefficients& coefficients,
                                  double reference_radius_m = kIgrfReferenceRadius_m);

  /// [nT] Field in the geocentric NED frame C at p (p.radius_m > 0).
  Eigen::Vector3d b_C_nT(const GeocentricPosition& p) const;
  /// [nT/yr] Secular variation of b_C_nT.
  Eigen::Vector3d bDot_C_nT_yr(const GeocentricPosition& p) const;

  /// [nT] (X, Y, Z) in the geodetic NED frame G at p.
  Eigen::Vector3d b_G_nT(const GeodeticPosition& p) const;
  /// [nT/yr] Secular variation of b_G_nT.
  Eigen::Vector3d bDot_G_nT_yr(const GeodeticPosition& p) const;

  /// X, Y, Z, H, F, D, I at p.
  MagneticElements elements(const GeodeticPosition& p) const;

  /// [T] Field at r_E_m [m] (Earth-fixed, ≠ 0) in E.
  Eigen::Vector3d b_E_T(const Eigen::Vector3d& r_E_m) const;
  /// [T] Field at r_N_m [m] (inertial) in N, the Earth turned by R_EN(jd_ut1).
  Eigen::Vector3d b_N_T(const Eigen::Vector3d& r_N_m, double jd_ut1) const;

  const GaussCoefficients& coefficients() const { return coefficients_; }
  double referenceRadius_m() const { return reference_radius_m_; }

 private:
  using Table = GaussCoefficients::Table;
  /// A geocentric point by its radius and the sines and cosines of its
  /// latitude and longitude: from Earth-fixed coordinates they are ratios of
  /// them, with no atan2 to find the angles and no sin or cos to undo it.
  struct Direction {
    double radius_m, sin_lat, cos_lat, sin_lon, cos_lon;
  };
  static Direction direction(const GeocentricPosition& p);
  Eigen::Vector3d synthesize(const Table& g, const Table& h, const Direction& p) const;

  GaussCoefficients coefficients_;
  double reference_radius_m_;
  // Degree-independent factors of the Legendre recursions, filled once.
  Table recursion_a_{};  // (2n − 1) / √(n² − m²), n > m
  Table recursion_b_{};  // √((n − 1)² − m²) / √(n² − m²), n > m
  Table root_n2_m2_{};   // √(n² − m²)
  std::array<double, GaussCoefficients::kMaxDegree + 1> sectoral_{};     // √(1 − 1/(2m)), m ≥ 2
  std::array<double, GaussCoefficients::kMaxDegree + 1> zonal_slope_{};  // √(n(n + 1)/2)
};

/// The field of igrf14Coefficients() (GeomagneticCoefficients.hpp).
/// @throws std::runtime_error as igrf14Coefficients().
SphericalHarmonicField igrf14(const std::string& igrf_coeff_file, double decimal_year);

/// The field of wmm2025Coefficients().
/// @throws std::runtime_error as wmm2025Coefficients().
SphericalHarmonicField wmm2025(const std::string& wmm_cof_file, double decimal_year);

}  // namespace flatsat::sim
