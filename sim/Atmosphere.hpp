// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim/Constants.hpp"

namespace flatsat::sim {

/// One altitude of a Harris–Priester table. The two densities are the ends of the
/// diurnal variation — below the antapex and below the apex of the day-side bulge —
/// for one level of solar activity; they are not solar-minimum / solar-maximum values.
struct HarrisPriesterRow {
  double height_m;           // [m] above the reference ellipsoid
  double density_min_kg_m3;  // [kg/m³] antapex density, > 0
  double density_max_kg_m3;  // [kg/m³] apex density, ≥ density_min_kg_m3
};

/// Montenbruck & Gill, Satellite Orbits, Table 3.8: the Harris–Priester table for mean
/// solar activity, 100–1000 km (converted from g/km³).
std::vector<HarrisPriesterRow> harrisPriesterMeanSolarActivity();

/// A Harris–Priester table from a text file, for the solar activity it was published for
/// (the density table is the model's solar-activity input: M&G §3.5.2; Orekit's
/// HarrisPriester takes it the same way). One row per line: height [km], antapex and apex
/// densities [g/km³], as M&G Table 3.8 and the GTDS tables print them; `#` starts a comment.
/// @throws std::runtime_error "FILE:LINE: reason" for an unreadable file or a malformed row
///         (the table's own checks are AtmosphereParams::validate()).
std::vector<HarrisPriesterRow> readHarrisPriesterTable(const std::string& path);

enum class DensityModel {
  kHarrisPriester,  // diurnal bulge, table for one solar activity (M&G §3.5.2)
  kExponential,     // static, Vallado Table 8-4
};

struct AtmosphereParams {
  DensityModel model = DensityModel::kHarrisPriester;
  /// [-] Harris–Priester cosine exponent n, [2, 6]: 2 for low-inclination orbits, 6 for
  /// polar ones (M&G §3.5.2); 4 is the usual compromise.
  double bulge_exponent = 4.0;
  /// Harris–Priester table, heights strictly increasing, ≥ 2 rows. The solar activity
  /// enters here: the default is M&G's mean-activity table; for another F10.7, load the
  /// table published for it (e.g. the GTDS tables of Long et al. 1989, F10.7 = 65…275).
  std::vector<HarrisPriesterRow> harris_priester_table = harrisPriesterMeanSolarActivity();

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// [m] Height above the WGS-84 ellipsoid, to first order in the flattening:
/// |r| − a(1 − f sin²φ') with φ' the geocentric latitude. From the surface to 1000 km
/// it is within 30 m of the geodetic height (geodeticFromEarthFixed), far less than a
/// density scale height (≥ 5 km), for one square root instead of the exact closed form
/// in every force evaluation. The ellipsoid's axis is taken as the z axis of r's frame,
/// so r may be inertial (N) or Earth-fixed.
double approximateHeight_m(const Eigen::Vector3d& r_m);

/// [m/s] Velocity relative to the air, which turns with the Earth about the N z axis
/// (equator of date ≈ ECI): v − ω⊕ ẑ × r. The wind the spacecraft feels is its negative.
inline Eigen::Vector3d velocityThroughAir_N_m_s(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s) {
  return v_N_m_s - kEarthRotationRate_rad_s * Eigen::Vector3d::UnitZ().cross(r_N_m);
}

/// [kg/m³] Exponential atmosphere, Vallado Table 8-4 (CIRA-72 based):
/// ρ = ρ0 exp(−(h − h0)/H) with the band whose base h0 is the highest not above h.
/// Heights below 0 use the sea-level band, those above 1000 km the 1000 km band.
double exponentialDensity_kg_m3(double height_m);

/// Atmospheric density for the drag model.
class Atmosphere {
 public:
  /// @throws std::invalid_argument listing every AtmosphereParams::validate() error.
  explicit Atmosphere(const AtmosphereParams& params);

  /// [kg/m³] Density at r_N_m [m] (inertial frame N) with the Sun in direction
  /// sun_N_unit (used by the diurnal bulge only). Harris–Priester outside its table
  /// continues the exponential of the first or last layer, so the density stays
  /// continuous (M&G instead set it to zero, which would switch drag off abruptly).
  double density_kg_m3(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& sun_N_unit) const;

 private:
  double harrisPriester_kg_m3(double height_m, double cos_psi) const;

  AtmosphereParams params_;
  // Per layer i (between rows i and i+1): [m] scale heights of the two profiles.
  std::vector<double> scale_height_min_m_;
  std::vector<double> scale_height_max_m_;
};

}  // namespace flatsat::sim
