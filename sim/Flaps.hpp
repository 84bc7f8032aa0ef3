// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sim/PanelModel.hpp"

namespace flatsat::sim {

inline constexpr int kFlapCount = 4;
/// Each plate is exposed on both sides: two panels per plate.
inline constexpr int kFlapPanelCount = 2 * kFlapCount;

/// The body axis the two flap wings extend along (seed S2). Polar orbits (the seed's
/// Figs. 2 and 3): along pitch y, the plates give roll and yaw. Equatorial orbit C
/// (Fig. 4, claim 8): along yaw z, the plates give roll and pitch, the axis the field
/// nearly lies along there and the coils cannot torque about.
enum class FlapWings { kAlongY, kAlongZ };

/// "y", "z" → wings; nullopt for anything else.
std::optional<FlapWings> flapWingsFromName(const std::string& name);

/// [-] Body direction of the flaps' second torque (the one c_az scales): yaw +z with the
/// wings along y; pitch −y with the wings along z (the along-y layout turned a quarter
/// about x: y → z, z → −y).
Eigen::Vector3d flapSecondAxis_B(FlapWings wings);

/// [-] c_ax x̂ + c_az · flapSecondAxis_B: the flaps' torque direction and size per K.
Eigen::Vector3d flapTorqueShape_B(const Eigen::Vector2d& c, FlapWings wings);

/// Aerodynamic flaps of seed S2 (CNES, FR2718105 / CN1148836).
struct FlapsParams {
  bool fitted = false;                        // no flaps unless set
  FlapWings wings = FlapWings::kAlongY;       // [-] wing axis: y (polar orbits) or z (equatorial, claim 8)
  double plate_area_m2 = 0.0;                 // [m²] A_p, each of the four plates (the seed's S/2), > 0
  double lever_arm_m = 0.0;                   // [m] l, centre of mass to a plate's centre along the wings, > 0
  double max_angle_rad = std::numbers::pi / 2;  // [rad] |θi| limit, (0, π/2]
  double specular = 0.0;                      // [-] optical fractions of both faces, as Panel
  double diffuse = 0.0;                       // [-]
  double absorbed = 1.0;                      // [-]
  double aero_specular = 1.0;                 // [-] σ; the seed assumes specular reflection (hard Cr₂O₃ coating)

  /// Every violation as "field: reason"; empty when valid (always when not fitted).
  std::vector<std::string> validate() const;
};

/// Geometry and sign conventions (re-derived from the seed; its plate numbering
/// text is garbled, its formulas are taken as the definition):
///  - body x is the roll axis along the orbit, pointing against the motion, so
///    the nominal wind (air relative to the spacecraft) is +x; z is the yaw axis
///    away from the Earth; y = z × x is the pitch axis, normal to the orbit plane.
///  - two wings along ±y; plates 1 and 3 on the +y wing, plates 2 and 4 on the
///    −y wing (the only assignment for which c_az's (−1)^i is the yaw of one-sided
///    drag and θ1 = −θ3 = θ2 = −θ4 cancels lift within each wing); plate centres
///    at (0, ±l, 0): a central plate and the pair of half plates around it share
///    the same centroid.
///  - θi turns plate i about its wing's outward axis (+y for the +y wing, −y for
///    the −y wing), from the neutral position in the x–y plane (edge-on to the
///    wind). The plate normal is then (±sin θi, 0, cos θi) with + on the +y wing.
/// With specular reflection and wind V along +x each plate gives the lift
/// 2ρA_pV² sin θ cos θ |sin θ| along z and the drag 2ρA_pV² |sin θ|³ along x,
/// hence about the centre of mass
///   τ = 2ρ A_p V² l · (c_ax, 0, c_az),
///   c_ax = Σ ½ sin 2θi |sin θi|,   c_az = Σ (−1)^i |sin θi|³
/// (algorithms.md's c_ax = Σ sin 2θi |sin θi| is twice this physical roll shape).
/// With the wings along z (claim 8) all of the above is turned a quarter about x:
/// plates 1, 3 on the +z wing, normals (±sin θi, −cos θi, 0), and τ = K (c_ax, −c_az, 0).
/// Derivation, and how the seed's factors read: docs/magnetic_control.md,
/// "The flaps' torque, derived".
class Flaps {
 public:
  /// Params must be valid and fitted.
  explicit Flaps(const FlapsParams& params);

  /// [rad] Commands limited to ±max_angle_rad; a non-finite angle → 0 (neutral).
  Eigen::Vector4d limitAngles(const Eigen::Vector4d& theta_cmd_rad) const;

  /// The eight faces (two per plate) at angles θ [rad], for the panel model:
  /// gives the flaps' force and torque for any wind and Sun direction.
  std::array<Panel, kFlapPanelCount> panels(const Eigen::Vector4d& theta_rad) const;

  /// [-] (c_ax, c_az) of the seed's closed form above.
  static Eigen::Vector2d normalisedTorques(const Eigen::Vector4d& theta_rad);

  /// [N m] The closed form τ = 2ρA_pV²l · flapTorqueShape_B(c) for wind V [m/s] along +x.
  Eigen::Vector3d nominalTorque_B_Nm(const Eigen::Vector4d& theta_rad, double density_kg_m3, double speed_m_s) const;

 private:
  FlapsParams params_;
};

}  // namespace flatsat::sim
