// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/SpinCapture.hpp"

#include <cmath>

#include "components/common/Validation.hpp"

namespace flatsat::unloading_controller {

std::vector<std::string> SpinCaptureParams::validate() const {
  std::vector<std::string> errors;
  requireUnit(errors, "spin_axis_B", spin_axis_B);
  require(errors, std::isfinite(spin_rate_rad_s), "spin_rate_rad_s", "must be finite");
  requirePositive(errors, "orbit_rate_rad_s", orbit_rate_rad_s);
  require(errors, std::isfinite(field_turn_per_orbit_rate), "field_turn_per_orbit_rate", "must be finite");
  require(errors, law != SpinLaw::kSeed || field_turn == FieldTurn::kOrbitRate, "field_turn",
          "the seed's law has only Q = B x w0 for the field's turn (field_turn: orbit_rate)");
  return errors;
}

BdotParams spinCaptureLaw(const SpinCaptureParams& params, const Eigen::Vector3d& max_dipole_Am2) {
  BdotParams law;
  law.shape = BdotShape::kBangBang;
  law.max_dipole_Am2 = max_dipole_Am2;
  if (params.law == SpinLaw::kSeed) {
    law.omega_ref_B_rad_s = params.orbit_rate_rad_s * params.spin_axis_B;  // P = Ḃ − B_k × ω0 a = Ḃ + ω0 a × B_k
    law.correction_at_sample = true;
    return law;
  }
  const double field_turn_rad_s =
      params.field_turn == FieldTurn::kModel ? 0.0 : params.field_turn_per_orbit_rate * params.orbit_rate_rad_s;
  law.omega_ref_B_rad_s = (params.spin_rate_rad_s - field_turn_rad_s) * params.spin_axis_B;
  return law;
}

}  // namespace flatsat::unloading_controller
