// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/Atmosphere.hpp"
#include "sim/Constants.hpp"

namespace flatsat::sim {

/// [m] Reference radius of the EGM2008 zonal coefficients below.
inline constexpr double kEgm2008Radius_m = 6378136.3;
/// [-] Zonal coefficients J_n = −√(2n+1) C̄_n0 of EGM2008 (tide-free; Pavlis et al.,
/// JGR 117, B04406, 2012): C̄20 = −0.484165143790815e-3, C̄30 = 0.957161207093473e-6,
/// C̄40 = 0.539965866638991e-6.
inline constexpr double kEgm2008J2 = 1.082626173852223e-3;
inline constexpr double kEgm2008J3 = -2.532410518567722e-6;
inline constexpr double kEgm2008J4 = -1.619897599916973e-6;
/// [-] Unnormalised sectoral C22, S22 of EGM2008: C̄22 = 0.243914352398e-5,
/// S̄22 = −0.140016683654e-5 times √(5/12) (Pavlis et al. 2012; the
/// normalisation of Montenbruck & Gill Eq. 3.13).
inline constexpr double kEgm2008C22 = 2.43914352398e-6 * 0.6454972243679028;
inline constexpr double kEgm2008S22 = -1.40016683654e-6 * 0.6454972243679028;
/// [m³/s²] Sun: IAU 2015 Resolution B3 nominal solar mass parameter (exact).
inline constexpr double kMuSun_m3_s2 = 1.3271244e20;
/// [m³/s²] Moon: the IAU 2009 Moon/Earth mass ratio 0.0123000371 (Luzum et al.,
/// Celest. Mech. Dyn. Astr. 110, 2011) times kMuEarth_m3_s2.
inline constexpr double kMuMoon_m3_s2 = 0.0123000371 * kMuEarth_m3_s2;
/// [N/m²] Solar radiation pressure at 1 AU, irradiance / c (M&G §3.4.1), with the total
/// solar irradiance 1361 W/m² of Kopp & Lean (GRL 38, L01706, 2011), as in PanelModel.
inline constexpr double kSolarPressure1Au_N_m2 = 1361.0 / 299792458.0;

/// Which forces act on the spacecraft, and its properties. Frame N = ECI (mean equator
/// and equinox of date, as the Sun and Moon ephemerides).
struct OrbitForceParams {
  bool central_gravity = true;  // μ/r² of a spherical Earth
  bool j2 = true;               // zonal harmonics of EGM2008, each switchable
  bool j3 = true;
  bool j4 = true;
  bool j22 = false;            // sectoral C22/S22: the longitude drift of a geostationary orbit
  bool drag = true;            // co-rotating atmosphere, `atmosphere` density
  bool solar_pressure = true;  // cannonball, conical Earth shadow
  bool sun_gravity = true;     // third-body perturbations
  bool moon_gravity = true;
  double mass_kg = 4.0;                   // [kg] > 0 (defaults: a 3U CubeSat)
  double drag_area_m2 = 0.03;             // [m²] ≥ 0, mean cross-section facing the flow
  double drag_coefficient = 2.2;          // [-] C_D in [0, 5]; 2.0–2.5 for LEO bodies
  double srp_area_m2 = 0.03;              // [m²] ≥ 0, mean cross-section facing the Sun
  double reflectivity_coefficient = 1.3;  // [-] C_R in [1, 2]: 1 absorbs, 2 mirrors
  AtmosphereParams atmosphere;            // density model for the drag
  double tt_minus_utc_s = 69.184;         // [s] in [32.184, 120]; 32.184 + 37 leap s since 2017

  /// Every violation as "field: reason", nested ones prefixed ("atmosphere.…").
  std::vector<std::string> validate() const;
};

/// What the forces need of the time at one instant: the geocentric Sun and
/// Moon in N, and the Earth's rotation angle for the tesseral terms.
struct Ephemerides {
  Eigen::Vector3d sun_N_m = Eigen::Vector3d::Zero();   // [m]
  Eigen::Vector3d moon_N_m = Eigen::Vector3d::Zero();  // [m]
  double earth_angle_rad = 0.0;                        // [rad] Greenwich sidereal angle (GMST)
};

/// [m/s²] Point-mass attraction −μ r/|r|³.
Eigen::Vector3d pointMassAcceleration_N(const Eigen::Vector3d& r_N_m, double mu_m3_s2);

/// [m/s²] Sum of the chosen zonal terms J2, J3, J4 of EGM2008, with the N z axis as
/// the Earth's figure axis (mean pole of date; nutation and polar motion, < 1e-4 rad,
/// are neglected, so no Earth-fixed transformation is needed for zonals). Gradient of
/// the potential −(μ/r) J_n (R/r)ⁿ P_n(s), s = z/r = sin(geocentric latitude):
/// a_n = μ J_n Rⁿ / r^(n+2) · [P'_(n+1)(s) r̂ − P'_n(s) ẑ].
Eigen::Vector3d zonalAcceleration_N(const Eigen::Vector3d& r_N_m, bool j2, bool j3, bool j4);

/// [m/s²] The sectoral degree-2 term in N, the Earth turned by
/// `earth_angle_rad` (GMST): the gradient of the potential
/// 3 μ R² [C22 (x² − y²) + 2 S22 x y] / r⁵ in Earth-fixed x, y, z
/// (P22(sin φ) = 3 cos² φ, Montenbruck & Gill Eq. 3.8).
Eigen::Vector3d sectoralJ22Acceleration_N(const Eigen::Vector3d& r_N_m, double earth_angle_rad);

/// [m/s²] Drag −½ ρ (C_D A/m) |v_rel| v_rel with v_rel = v − ω⊕ × r, the velocity
/// relative to an atmosphere rotating with the Earth (M&G §3.5.1).
/// @param ballistic_m2_kg C_D A/m [m²/kg].
Eigen::Vector3d dragAcceleration_N(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s, double density_kg_m3,
                                   double ballistic_m2_kg);

/// [m/s²] Cannonball solar radiation pressure −ν P⊙ C_R (A/m) (1 AU/d)² d̂, d the
/// satellite → Sun vector and ν = illumination() (M&G §3.4.1–3.4.2).
/// @param cr_area_over_mass_m2_kg C_R A/m [m²/kg].
Eigen::Vector3d solarPressureAcceleration_N(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& sun_N_m,
                                            double cr_area_over_mass_m2_kg);

/// [m/s²] Perturbation by a distant point mass at s: μ [(s − r)/|s − r|³ − s/|s|³],
/// the direct attraction less the Earth's (indirect term), M&G Eq. 3.37.
Eigen::Vector3d thirdBodyAcceleration_N(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& body_N_m, double mu_m3_s2);

/// Sum of the switched-on forces per unit mass.
class OrbitForces {
 public:
  /// @throws std::invalid_argument listing every OrbitForceParams::validate() error.
  explicit OrbitForces(const OrbitForceParams& params);

  /// Sun and Moon at jd_tt [d] (Vallado Alg. 29 and 31), each only if a switched-on
  /// force uses it; the other stays zero. The Earth's angle with UT1 = UTC.
  Ephemerides ephemeridesAt(double jd_tt) const;

  /// [m/s²] Acceleration in N at r [m], v [m/s] with the given Sun and Moon.
  Eigen::Vector3d acceleration_N(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s,
                                 const Ephemerides& bodies) const;

  const OrbitForceParams& params() const { return params_; }

 private:
  OrbitForceParams params_;
  Atmosphere atmosphere_;
  double ballistic_m2_kg_;          // C_D A/m
  double cr_area_over_mass_m2_kg_;  // C_R A/m
};

}  // namespace flatsat::sim
