// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <optional>

#include <Eigen/Dense>

#include "sim/GeomagneticField.hpp"
#include "sim/KeplerOrbit.hpp"
#include "sim/OrbitTrack.hpp"
#include "sim/SphericalHarmonicField.hpp"
#include "sim/SpotFieldModel.hpp"
#include "sim/Time.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::onboard {

/// Onboard knowledge the flight components compare their sensors with: an
/// orbit propagator, a field model and a Sun ephemeris, as an onboard computer
/// carries them (the vehicle's onboard view: vehicle/VehicleDescription.hpp).
struct ReferenceModelParams {
  sim::UtcEpoch epoch;               // scenario epoch (t = 0), UTC
  sim::OrbitElements orbit;          // onboard orbit knowledge at the epoch
  sim::OrbitTrackParams orbit_track; // onboard propagator (Kepler, or numerical with its forces)
  sim::DipoleCoefficients field;     // [nT] onboard field model coefficients (tilted dipole)
  /// [nT] when set, the onboard field model is this spherical-harmonic model (IGRF, WMM)
  /// instead of the dipole: seed S0 needs the field's direction to better than a degree.
  std::optional<sim::GaussCoefficients> field_harmonics;
  /// When set, the onboard field is seed S2's orbit-harmonic SPOT model (claim 5): a
  /// function of the argument of latitude in the orbit frame, no Earth rotation.
  std::optional<sim::SpotFieldModel> field_spot;
  /// [s] the field model and the Sun ephemeris are evaluated at t = j·field_node_s
  /// only and extrapolated in between from the newest three (0..10; 0: at every
  /// step). See ReferenceModel.
  double field_node_s = 1.0;
  std::vector<std::string> validate() const;
};

/// The reference model of a vehicle's onboard view: its epoch, orbit
/// knowledge (a numerical propagator's drag from its density model) and field
/// model (spherical harmonics to its degree, or the tilted dipole), with the
/// field evaluated at nodes `field_node_s` [s] apart.
ReferenceModelParams referenceModelOf(const vehicle::VehicleDescription& onboard, double field_node_s);

struct ReferenceVectors {
  Eigen::Vector3d sun_N_unit = Eigen::Vector3d::UnitX();  // [-] spacecraft -> Sun, inertial
  Eigen::Vector3d b_N_T = Eigen::Vector3d::Zero();        // [T] field at the spacecraft, inertial
  Eigen::Vector3d orbit_normal_N_unit = Eigen::Vector3d::UnitZ();  // [-] r × v / |r × v|, inertial
  Eigen::Vector3d r_N_m = Eigen::Vector3d::Zero();        // [m] onboard position, inertial
  Eigen::Vector3d v_N_m_s = Eigen::Vector3d::Zero();      // [m/s] onboard velocity, inertial
};

/// Onboard reference vectors at a time. The field model and the Sun's
/// position are evaluated at the nodes t_j = j·h (h = field_node_s) and
/// extrapolated in between by the quadratic through the nodes j−2, j−1, j
/// (Lagrange); the error is at most h³·max|b⃛|, about 1e-8 of the field at
/// h = 1 s in a low orbit. Derivation and measured figures: docs/onboard.md,
/// "The reference model between its nodes". Without three consecutive nodes
/// (the start, a jump in time) it evaluates exactly.
class ReferenceModel {
 public:
  using Params = ReferenceModelParams;
  explicit ReferenceModel(const Params& params);
  void reset() {
    orbit_.reset();
    nodes_ = 0;
  }
  /// Times must not decrease (the onboard propagator integrates forward).
  ReferenceVectors step(std::int64_t t_ns);

 private:
  struct Node {
    long long index = 0;        // j: at t = j·field_node_s
    Eigen::Vector3d b_N_T;      // [T] field at the onboard position
    Eigen::Vector3d r_sun_N_m;  // [m] the Sun from the Earth's centre
  };
  /// [T] The model's field at r_N_m [m] moving at v_N_m_s [m/s] (inertial), at the Julian
  /// date jd (UTC ≈ UT1).
  Eigen::Vector3d fieldAt(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s, double jd) const;
  /// [m] The Sun's position (inertial, from the Earth's centre) at t_s [s] after the epoch.
  Eigen::Vector3d sunAt(double t_s) const;
  /// Adds the node of t_s's interval when it is new; whether the three newest
  /// nodes are consecutive and end there (else the models are evaluated exactly).
  bool takeNodes(double t_s);
  /// The nodes' `quantity` at t_s, from the three newest.
  Eigen::Vector3d extrapolated(double t_s, Eigen::Vector3d Node::*quantity) const;

  Params params_;
  sim::OrbitTrack orbit_;
  std::array<Node, 3> node_{};  // the newest last
  int nodes_ = 0;               // how many of node_ hold a node

  sim::TiltedDipoleField field_;
  std::optional<sim::SphericalHarmonicField> harmonics_;
  double jd_epoch_;  // [d] UTC ≈ UT1
};

}  // namespace flatsat::onboard
