// SPDX-License-Identifier: Apache-2.0
#include "sim/GeomagneticField.hpp"

#include <cmath>

#include "sim/GeomagneticCoefficients.hpp"

namespace flatsat::sim {

DipoleCoefficients igrfDipoleAt(const std::string& igrf_coeff_file, double decimal_year) {
  // The full table's parser, so both models read a file the same way and report
  // the same faults; only the degree-1 terms are kept.
  const GaussCoefficients c = igrf14Coefficients(igrf_coeff_file, decimal_year);
  return DipoleCoefficients{c.g_nT[1][0], c.g_nT[1][1], c.h_nT[1][1]};
}

TiltedDipoleField::TiltedDipoleField(const DipoleCoefficients& coefficients, double reference_radius_m)
    : g_E_nT_(coefficients.g11_nT, coefficients.h11_nT, coefficients.g10_nT), reference_radius_m_(reference_radius_m) {}

Eigen::Vector3d TiltedDipoleField::b_E_T(const Eigen::Vector3d& r_E_m) const {
  // IGRF scalar potential (Alken et al. 2021, "International Geomagnetic Reference
  // Field: the thirteenth generation", Earth Planets Space 73:49, Eq. 1):
  //   V = a Σ_n Σ_m (a/r)^(n+1) [g_n^m cos mφ + h_n^m sin mφ] P_n^m(cos θ),  B = −∇V.
  // Degree 1 with Schmidt P_1^0 = cos θ, P_1^1 = sin θ and the unit vector
  // r̂ = (sin θ cos φ, sin θ sin φ, cos θ) in Earth-fixed axes:
  //   V = a (a/r)² (g·r̂) = a³ (g·r)/r³,  g = (g11, h11, g10),
  //   B = −∇V = −a³ [g/r³ − 3 (g·r) r/r⁵] = (a/r)³ [3 (g·r̂) r̂ − g].
  const double r = r_E_m.norm();
  const Eigen::Vector3d r_hat = r_E_m / r;
  const double scale = std::pow(reference_radius_m_ / r, 3) * 1e-9;  // nT → T
  return scale * (3.0 * g_E_nT_.dot(r_hat) * r_hat - g_E_nT_);
}

}  // namespace flatsat::sim
