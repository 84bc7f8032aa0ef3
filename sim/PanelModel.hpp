// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace flatsat::sim {

/// [W/m²] Total solar irradiance at 1 AU (Kopp & Lean 2011, Geophys. Res. Lett. 38, L01706).
inline constexpr double kSolarFlux1Au_W_m2 = 1361.0;
/// [m/s] Speed of light (SI, exact).
inline constexpr double kSpeedOfLight_m_s = 299792458.0;

/// One flat, one-sided surface element of the spacecraft. A plate exposed on
/// both sides is two panels with opposite normals. Shadowing and reflections
/// between panels are ignored.
struct Panel {
  double area_m2 = 0.0;                                 // [m²] > 0
  Eigen::Vector3d normal_B = Eigen::Vector3d::UnitX();  // [-] unit outward normal, body axes
  Eigen::Vector3d r_cp_B_m = Eigen::Vector3d::Zero();   // [m] centre of pressure from the centre of mass
  double specular = 0.0;                                // [-] ρs, light reflected specularly, 0..1
  double diffuse = 0.0;                                 // [-] ρd, light reflected diffusely (Lambertian), 0..1
  double absorbed = 1.0;                                // [-] ρa, light absorbed, 0..1; ρs + ρd + ρa = 1
  double aero_specular = 0.0;  // [-] σ, molecules reflected specularly, 0..1; the rest stick (see below)
  /// [-] unit: a solar-array drive turns the panel about this body axis to face
  /// the Sun (its centre of pressure on the axis stays put); zero: fixed at normal_B.
  Eigen::Vector3d sun_tracking_axis_B = Eigen::Vector3d::Zero();

  /// The outward normal with the Sun at sun_B_unit: normal_B for a fixed
  /// panel, or for a zero sun_B_unit or one along the axis; else the unit
  /// vector normal to the axis nearest the Sun.
  Eigen::Vector3d normalFacing(const Eigen::Vector3d& sun_B_unit) const {
    return sun_tracking_axis_B.isZero(0.0) ? normal_B : trackedNormal(sun_B_unit);
  }

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;

 private:
  Eigen::Vector3d trackedNormal(const Eigen::Vector3d& sun_B_unit) const;
};

/// Force on the spacecraft [N] and its torque about the centre of mass [N m], body axes.
struct ForceTorque {
  Eigen::Vector3d force_B_N = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque_B_Nm = Eigen::Vector3d::Zero();

  ForceTorque& operator+=(const ForceTorque& other) {
    force_B_N += other.force_B_N;
    torque_B_Nm += other.torque_B_Nm;
    return *this;
  }
};

/// [W/m²] Solar flux at the spacecraft: kSolarFlux1Au_W_m2 · illumination · (1 AU / r)².
/// @param sun_distance_m [m] spacecraft to Sun centre.  @param illumination [-] 1 Sun, 0 umbra.
double solarFlux_W_m2(double sun_distance_m, double illumination);

/// Free-molecular (hyperthermal) flow on one panel, wind w = air velocity
/// relative to the spacecraft, V = |w|, ŵ = w / V. A panel faces the flow when
/// cos α = −n·ŵ > 0 and intercepts the mass flow ρ V A cos α. The fraction 1 − σ
/// sticks and is re-emitted with negligible speed (full accommodation: all its
/// momentum goes along ŵ, C_D = 2 on a face-on plate); the fraction σ reflects
/// specularly and reverses its normal momentum:
///   F = ρ V² A cos α [(1 − σ) ŵ − 2σ cos α n],   τ = r_cp × F.
/// σ = 0 is the drag model F = −½ ρ C_D V² A cos α v̂ with C_D = 2, v̂ = −ŵ
/// (Markley & Crassidis, Fundamentals of Spacecraft Attitude Determination and
/// Control, §3.3.6, aerodynamic torque; Wertz, Spacecraft Attitude Determination
/// and Control, §17.2);
/// σ = 1 is the specular model of seed S2 (F dt = dm · 2 V sin θ, normal to the plate).
/// @param density_kg_m3 [kg/m³] ≥ 0.  @param wind_B_m_s [m/s] body axes.
/// @param sun_B_unit [-] the Sun, which a sun-tracking panel faces (zero: as mounted).
ForceTorque aerodynamicForceTorque(const Panel& panel, double density_kg_m3, const Eigen::Vector3d& wind_B_m_s,
                                   const Eigen::Vector3d& sun_B_unit = Eigen::Vector3d::Zero());
/// Sum of aerodynamicForceTorque over the panels.
ForceTorque aerodynamicForceTorque(std::span<const Panel> panels, double density_kg_m3,
                                   const Eigen::Vector3d& wind_B_m_s,
                                   const Eigen::Vector3d& sun_B_unit = Eigen::Vector3d::Zero());

/// Solar radiation pressure on one panel, P = flux / c, ŝ the unit vector to the
/// Sun, n = normalFacing(ŝ), lit when cos θ = n·ŝ > 0:
///   F = −P A cos θ [(1 − ρs) ŝ + 2(ρs cos θ + ρd / 3) n],   τ = r_cp × F
/// (Markley & Crassidis Eqs. 3.167–3.169; Wertz §17.2, pp. 570–573, with the
/// three optical fractions). Absorbed and diffuse light deliver their incoming momentum along
/// −ŝ; specular light doubles its normal component; Lambertian re-emission adds
/// 2/3 of the normal momentum.
/// @param sun_B_unit [-] spacecraft → Sun, unit, body axes.  @param flux_W_m2 [W/m²] ≥ 0.
ForceTorque solarPressureForceTorque(const Panel& panel, const Eigen::Vector3d& sun_B_unit, double flux_W_m2);
/// Sum of solarPressureForceTorque over the panels.
ForceTorque solarPressureForceTorque(std::span<const Panel> panels, const Eigen::Vector3d& sun_B_unit,
                                     double flux_W_m2);

}  // namespace flatsat::sim
