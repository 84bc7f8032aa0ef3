// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <string>

#include <Eigen/Core>

#include "sim/Constants.hpp"

namespace flatsat::sim {

/// Degree-1 Gauss coefficients (Schmidt semi-normalised) of the main field.
struct DipoleCoefficients {
  double g10_nT = -29350.0;  // [nT] IGRF-14, 2025.0
  double g11_nT = -1410.3;   // [nT]
  double h11_nT = 4545.5;    // [nT]
};

/// The degree-1 terms of igrf14Coefficients() at decimal_year [yr] (IGRF-14 layout:
/// rows "g|h n m", one column per 5-year epoch, then the secular variation [nT/yr]
/// for the five years after the last epoch; linear in time between epochs, last
/// epoch + (t − last)·SV after it).
/// @throws std::runtime_error naming the file, the line and the reason when the
///         file is missing or malformed or the year is outside the table.
DipoleCoefficients igrfDipoleAt(const std::string& igrf_coeff_file, double decimal_year);

/// Field of the degree-1 spherical harmonic expansion: a dipole at the Earth's
/// centre, tilted and sized by g10, g11, h11.
class TiltedDipoleField {
 public:
  explicit TiltedDipoleField(const DipoleCoefficients& coefficients,
                             double reference_radius_m = kIgrfReferenceRadius_m);

  /// [T] Field at r_E_m [m] (Earth-fixed, from the Earth's centre, r ≠ 0).
  Eigen::Vector3d b_E_T(const Eigen::Vector3d& r_E_m) const;

 private:
  Eigen::Vector3d g_E_nT_;  // (g11, h11, g10)
  double reference_radius_m_;
};

}  // namespace flatsat::sim
