// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <optional>

#include "sim/GeomagneticField.hpp"
#include "sim/KeplerOrbit.hpp"
#include "sim/OrbitTrack.hpp"
#include "sim/SphericalHarmonicField.hpp"
#include "sim/Time.hpp"

namespace flatsat::estimator {

/// Onboard knowledge the estimator compares its sensors with: an orbit
/// propagator, a field model and a Sun ephemeris (the same models the
/// dynamics server uses, as an onboard computer would carry them).
struct ReferenceModelParams {
  sim::UtcEpoch epoch;               // scenario epoch (t = 0), UTC
  sim::OrbitElements orbit;          // onboard orbit knowledge at the epoch
  sim::OrbitTrackParams orbit_track; // onboard propagator (Kepler, or numerical with its forces)
  sim::DipoleCoefficients field;     // [nT] onboard field model coefficients (tilted dipole)
  /// [nT] when set, the onboard field model is this spherical-harmonic model (IGRF, WMM)
  /// instead of the dipole: seed S0 needs the field's direction to better than a degree.
  std::optional<sim::GaussCoefficients> field_harmonics;
  std::vector<std::string> validate() const;
};

struct ReferenceVectors {
  Eigen::Vector3d sun_N_unit = Eigen::Vector3d::UnitX();  // [-] spacecraft -> Sun, inertial
  Eigen::Vector3d b_N_T = Eigen::Vector3d::Zero();        // [T] field at the spacecraft, inertial
  Eigen::Vector3d orbit_normal_N_unit = Eigen::Vector3d::UnitZ();  // [-] r × v / |r × v|, inertial
  Eigen::Vector3d r_N_m = Eigen::Vector3d::Zero();        // [m] onboard position, inertial
  Eigen::Vector3d v_N_m_s = Eigen::Vector3d::Zero();      // [m/s] onboard velocity, inertial
};

class ReferenceModel {
 public:
  using Params = ReferenceModelParams;
  explicit ReferenceModel(const Params& params);
  void reset() { orbit_.reset(); }
  /// Times must not decrease (the onboard propagator integrates forward).
  ReferenceVectors step(std::int64_t t_ns);

 private:
  Params params_;
  sim::OrbitTrack orbit_;
  sim::TiltedDipoleField field_;
  std::optional<sim::SphericalHarmonicField> harmonics_;
  double jd_epoch_;  // [d] UTC ≈ UT1
};

}  // namespace flatsat::estimator
