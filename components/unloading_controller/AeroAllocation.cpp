// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/AeroAllocation.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "components/common/Validation.hpp"

namespace flatsat::unloading_controller {

std::optional<AeroSplit> aeroSplitFromName(const std::string& name) {
  if (name == "magnetic_aero") return AeroSplit::kMagneticAero;
  if (name == "flaps_only") return AeroSplit::kFlapsOnly;
  if (name == "drag_only") return AeroSplit::kDragOnly;
  return std::nullopt;
}

std::vector<std::string> AeroAllocationParams::validate() const {
  std::vector<std::string> errors;
  requireAllPositive(errors, "max_dipole_Am2", max_dipole_Am2, "coil");
  append(errors, flaps.validate());
  require(errors, drag_only_angle_rad >= 0.0 && drag_only_angle_rad <= flaps.max_angle_rad, "drag_only_angle_rad",
          "must be in [0, max_angle_rad]");
  requirePositive(errors, "min_field_T", min_field_T);
  return errors;
}

AeroAllocation::AeroAllocation(const Params& params)
    : params_(validated(params, "AeroAllocationParams")), inversion_(params.flaps) {}

AeroAllocationOutput AeroAllocation::step(const Input& in, std::int64_t /*t_ns*/) const {
  Output out;
  const Eigen::Vector3d& B = in.b_B_T;
  const Eigen::Vector3d& C = in.c_demand_B_Nm;
  const double b_sq = B.squaredNorm();
  const Eigen::Vector3d second = sim::flapSecondAxis_B(params_.wings);
  const double d = fieldInFlapPlane_B(B, params_.wings).squaredNorm();
  const double min_sq = params_.min_field_T * params_.min_field_T;
  if (params_.split == AeroSplit::kDragOnly) out.flaps = inversion_.dragOnly(params_.drag_only_angle_rad);
  if (!C.allFinite() || !(b_sq >= min_sq) || !std::isfinite(b_sq) || C.isZero(0.0)) return out;

  // Eq. II: the flaps' share; kDragOnly's flaps give none, so its coils give C⊥B only.
  Eigen::Vector3d c_aero = Eigen::Vector3d::Zero();
  const bool air = in.flap_scale_Nm > 0.0 && std::isfinite(in.flap_scale_Nm);
  if (air && params_.split == AeroSplit::kMagneticAero && d >= min_sq) {
    c_aero = leastFlapTorque_B_Nm(C, B, params_.wings);
  } else if (air && params_.split == AeroSplit::kFlapsOnly) {
    c_aero = C.x() * Eigen::Vector3d::UnitX() + C.dot(second) * second;
  }
  // Only the part ⟂ B is magnetic: M = B × C_M/|B|² gives M × B = C_M exactly when C_M ⟂ B.
  Eigen::Vector3d c_mag = C - c_aero;
  c_mag -= B * (B.dot(c_mag) / b_sq);
  Eigen::Vector3d m = B.cross(c_mag) / b_sq;

  double share = 1.0;
  const double coil_share = (params_.max_dipole_Am2.array() / m.array().abs()).minCoeff();
  if (coil_share < 1.0) {
    share = coil_share;
    out.coils_saturated = true;
  }
  if (!c_aero.isZero(0.0)) {
    const FlapSolution flaps =
        inversion_.solve(share * Eigen::Vector2d(c_aero.x(), c_aero.dot(second)) / in.flap_scale_Nm);
    if (flaps.scale < 1.0) out.flaps_saturated = true;
    share *= flaps.scale;
    // The coils follow the flaps' share so that what is delivered stays along C.
    out.flaps = flaps;
  }
  out.delivered = share;
  out.m_B_Am2 = share * m;
  out.c_magnetic_B_Nm = out.m_B_Am2.cross(B);
  out.c_aero_B_Nm = in.flap_scale_Nm * sim::flapTorqueShape_B(out.flaps.c_achieved, params_.wings);
  return out;
}

}  // namespace flatsat::unloading_controller
