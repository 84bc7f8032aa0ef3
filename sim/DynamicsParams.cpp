// SPDX-License-Identifier: Apache-2.0
#include "sim/DynamicsParams.hpp"

#include <cmath>

#include "sim/Format.hpp"

namespace flatsat::sim {
namespace {

constexpr double kUnitNormTolerance = 1e-6;

void appendNested(const std::string& prefix, const std::vector<std::string>& nested, std::vector<std::string>& errors) {
  for (const std::string& error : nested) errors.push_back(prefix + "." + error);
}

void appendHarmonicsErrors(const GaussCoefficients& c, std::vector<std::string>& errors) {
  if (c.degree < 1 || c.degree > GaussCoefficients::kMaxDegree) {
    errors.push_back("field_harmonics.degree: " + std::to_string(c.degree) + " must be in 1..13");
    return;
  }
  bool finite = true;
  for (int n = 1; n <= c.degree; ++n) {
    for (int m = 0; m <= n; ++m) finite = finite && std::isfinite(c.g_nT[n][m]) && std::isfinite(c.h_nT[n][m]);
  }
  if (!finite) errors.push_back("field_harmonics: Gauss coefficients must be finite");
  if (c.g_nT[1][0] == 0.0) errors.push_back("field_harmonics: no coefficients (g10 = 0)");
}

}  // namespace

std::vector<std::string> DynamicsParams::validate() const {
  std::vector<std::string> errors;
  appendNested("epoch", epoch.validate(), errors);
  appendNested("orbit", orbit.validate(), errors);
  appendNested("orbit_track", orbit_track.validate(), errors);
  if (orbit_track.propagator == OrbitPropagation::kNumerical && orbit_track.forces.drag && !atmosphere) {
    errors.push_back(
        "orbit_track.forces.drag: needs an atmosphere model (the constant density is for the panels only)");
  }
  const std::vector<std::string> body_errors = body.validate();
  appendNested("body", body_errors, errors);

  if (!std::isfinite(field.g10_nT) || !std::isfinite(field.g11_nT) || !std::isfinite(field.h11_nT)) {
    errors.push_back("field: Gauss coefficients must be finite");
  }
  if (field_degree < 1 || field_degree > GaussCoefficients::kMaxDegree) {
    errors.push_back("field_degree: " + std::to_string(field_degree) + " must be in 1..13");
  }
  if (field_model == FieldModel::kSphericalHarmonics) appendHarmonicsErrors(field_harmonics, errors);
  if (!torquer_max_dipole_Am2.allFinite() || (torquer_max_dipole_Am2.array() < 0.0).any()) {
    errors.push_back("torquer_max_dipole_Am2: every coil limit must be finite and ≥ 0");
  }
  if (!residual_dipole_B_Am2.allFinite()) errors.push_back("residual_dipole_B_Am2: must be finite");
  for (std::size_t i = 0; i < panels.size(); ++i) {
    appendNested("panels[" + std::to_string(i) + "]", panels[i].validate(), errors);
  }
  if (thrusters.size() > static_cast<std::size_t>(kMaxThrusters)) {
    errors.push_back("thrusters: " + std::to_string(thrusters.size()) + " thrusters, at most " +
                     std::to_string(kMaxThrusters));
  }
  for (std::size_t i = 0; i < thrusters.size(); ++i) {
    appendNested("thrusters[" + std::to_string(i) + "]", thrusters[i].validate(), errors);
  }
  appendNested("flaps", flaps.validate(), errors);
  if (atmosphere) appendNested("atmosphere", atmosphere->validate(), errors);
  if (!(density_kg_m3 >= 0.0) || !std::isfinite(density_kg_m3)) {
    errors.push_back("density_kg_m3: " + formatNumber(density_kg_m3) + " must be finite and ≥ 0");
  }
  if (!disturbance_torque_B_Nm.allFinite()) errors.push_back("disturbance_torque_B_Nm: must be finite");
  if (substeps < 1) errors.push_back("substeps: " + std::to_string(substeps) + " must be ≥ 1");
  if (!q0_NB.coeffs().allFinite() || std::abs(q0_NB.norm() - 1.0) > kUnitNormTolerance) {
    errors.push_back("q0_NB: must be a unit quaternion (norm " + formatNumber(q0_NB.norm()) + ")");
  }
  if (!w0_NB_B_rad_s.allFinite()) errors.push_back("w0_NB_B_rad_s: must be finite");
  if (!wheel_speed0_rad_s.allFinite()) {
    errors.push_back("wheel_speed0_rad_s: must be finite");
  } else if (body_errors.empty()) {
    for (int i = 0; i < body.wheel_count; ++i) {
      const double momentum = body.wheel_inertia_kg_m2(i) * wheel_speed0_rad_s(i);
      if (std::abs(momentum) > body.wheel_max_momentum_Nms(i)) {
        errors.push_back("wheel_speed0_rad_s[" + std::to_string(i) + "]: momentum " + formatNumber(momentum) +
                         " N m s exceeds body.wheel_max_momentum_Nms " + formatNumber(body.wheel_max_momentum_Nms(i)));
      }
    }
  }
  return errors;
}

}  // namespace flatsat::sim
