// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/unloading_controller/FlapInversion.hpp"
#include "sim/Flaps.hpp"

namespace flatsat::unloading_controller {

/// How a demanded torque is split between the coils and the S2 flaps.
enum class AeroSplit {
  kMagneticAero,  // seed S2: the coils take all they can, the flaps the rest (least drag)
  kFlapsOnly,     // the flaps take roll and yaw, the coils pitch only: the seed's comparison
  kDragOnly       // the coils as kMagneticAero's magnetic part; the flaps brake without torque
};

/// "magnetic_aero", "flaps_only", "drag_only" → split; nullopt for anything else.
std::optional<AeroSplit> aeroSplitFromName(const std::string& name);

struct AeroAllocationParams {
  AeroSplit split = AeroSplit::kMagneticAero;
  Eigen::Vector3d max_dipole_Am2 = Eigen::Vector3d::Constant(1.0);  // [A m²] per-coil limit, > 0
  FlapInversionParams flaps;        // [-] angle limit and failed plates
  sim::FlapWings wings = sim::FlapWings::kAlongY;  // [-] the flaps' torque plane: roll–yaw (y) or roll–pitch (z)
  double drag_only_angle_rad = 0.0;  // [rad] θ of kDragOnly, [0, flaps.max_angle_rad]
  double min_field_T = 1.0e-6;       // [T] |B| (and B's part in the flaps' plane) below this: no split, > 0

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct AeroAllocationInput {
  Eigen::Vector3d c_demand_B_Nm = Eigen::Vector3d::Zero();  // [N m] torque asked for, body
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();          // [T] field, body (x roll, y pitch, z yaw)
  /// [N m] K = 2ρA_pV²l of the flaps (Flaps.hpp): their torque is K·flapTorqueShape_B(c); <= 0: no air.
  double flap_scale_Nm = 0.0;
};

struct AeroAllocationOutput {
  Eigen::Vector3d m_B_Am2 = Eigen::Vector3d::Zero();       // [A m²] dipole command
  Eigen::Vector3d c_magnetic_B_Nm = Eigen::Vector3d::Zero();  // [N m] M × B it gives
  Eigen::Vector3d c_aero_B_Nm = Eigen::Vector3d::Zero();   // [N m] K·flapTorqueShape_B(c) of the angles
  FlapSolution flaps;                                      // angles and branch
  double delivered = 0.0;   // [-] share of the demand delivered (1: all; direction kept)
  bool coils_saturated = false;
  bool flaps_saturated = false;
};

/// [-] B's part in the plane of the flaps' two torque axes: (Bx, 0, Bz) with the wings
/// along y, (Bx, By, 0) along z.
inline Eigen::Vector3d fieldInFlapPlane_B(const Eigen::Vector3d& b_B_T, sim::FlapWings wings) {
  const Eigen::Vector3d second = sim::flapSecondAxis_B(wings);
  return b_B_T.x() * Eigen::Vector3d::UnitX() + b_B_T.dot(second) * second;
}

/// [N m] Eq. II: the least flap torque, in the flaps' plane only, that completes the demand c
/// with a torque ⟂ b. Wings along y (polar): C_A = (Bx, 0, Bz)(B·C)/(Bx² + Bz²); along z
/// (equatorial, claim 8): C_A = (Bx, By, 0)(B·C)/(Bx² + By²). The caller keeps B's part in
/// the plane away from 0.
inline Eigen::Vector3d leastFlapTorque_B_Nm(const Eigen::Vector3d& c_demand_B_Nm, const Eigen::Vector3d& b_B_T,
                                            sim::FlapWings wings) {
  const Eigen::Vector3d b_plane = fieldInFlapPlane_B(b_B_T, wings);
  return b_plane * (b_B_T.dot(c_demand_B_Nm) / b_plane.squaredNorm());
}

/// Seed S2's minimum-drag split (CNES FR2718105 / CN1148836, eqs. I–III; algorithms.md S2).
/// The coils cannot torque along B. With the flaps acting about roll x and yaw z only, the
/// smallest flap torque that completes C is C_A = (Bx, 0, Bz)(B·C)/(Bx² + Bz²) (eq. II):
/// C − C_A is then ⟂ B, and M = B × (C − C_A)/|B|² gives it exactly (M ⟂ B). |C_A| is the
/// component of C along B divided by the cosine of B's angle to the roll–yaw plane: the
/// least any flap pair can give; with B in that plane (polar orbit) it is that component.
/// With the wings along z (equatorial orbit, claim 8) the plane is roll–pitch and B lies
/// near pitch: the same with y for z.
/// kFlapsOnly gives the flaps C's part in their plane (roll and yaw, or roll and pitch),
/// and the coils the third axis.
/// A coil or flap limit scales the whole demand down by one factor, so what is delivered
/// stays along C. Flap angles come from FlapInversion on c = C_A/K.
class AeroAllocation {
 public:
  using Params = AeroAllocationParams;
  using Input = AeroAllocationInput;
  using Output = AeroAllocationOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit AeroAllocation(const Params& params);

  /// Stateless: nothing to forget; kept for the common API.
  void reset() {}

  Output step(const Input& in, std::int64_t t_ns) const;

  const Params& params() const { return params_; }

 private:
  Params params_;
  FlapInversion inversion_;
};

}  // namespace flatsat::unloading_controller
