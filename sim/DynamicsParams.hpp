// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim/Atmosphere.hpp"
#include "sim/Flaps.hpp"
#include "sim/GeomagneticCoefficients.hpp"
#include "sim/GeomagneticField.hpp"
#include "sim/KeplerOrbit.hpp"
#include "sim/OrbitTrack.hpp"
#include "sim/PanelModel.hpp"
#include "sim/RigidBodyWheels.hpp"
#include "sim/Thrusters.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {

/// The geomagnetic field of the truth.
enum class FieldModel {
  kTiltedDipole,        // DynamicsParams::field, IGRF degree 1
  kSphericalHarmonics,  // DynamicsParams::field_harmonics (IGRF-14, WMM2025) to field_degree
};

struct DynamicsParams {
  UtcEpoch epoch;              // scenario epoch (t = 0), UTC; UT1 taken equal to UTC
  OrbitElements orbit;         // osculating elements at the epoch, inertial frame N = ECI
  OrbitTrackParams orbit_track;  // Kepler or numerical (forces, mass, areas, step)
  RigidBodyParams body;        // inertia and reaction wheels (with friction)
  FieldModel field_model = FieldModel::kTiltedDipole;
  DipoleCoefficients field;    // [nT] degree-1 IGRF coefficients for the scenario's year
  GaussCoefficients field_harmonics;  // [nT] kSphericalHarmonics: at the epoch's decimal year, held for the run
  int field_degree = GaussCoefficients::kMaxDegree;  // [-] kSphericalHarmonics: highest degree used, 1..13
  Eigen::Vector3d torquer_max_dipole_Am2 = Eigen::Vector3d::Zero();   // [A m²] per coil (body x, y, z), ≥ 0
  Eigen::Vector3d residual_dipole_B_Am2 = Eigen::Vector3d::Zero();    // [A m²] spacecraft's own dipole, always on
  std::vector<Panel> panels;                // surface model for drag and solar pressure; none by default
  std::vector<ThrusterParams> thrusters;    // at most kMaxThrusters; none by default
  FlapsParams flaps;                        // seed S2 flaps; not fitted by default
  /// Density model for the panels' drag and the numerical orbit's drag (whose
  /// orbit_track.forces.atmosphere it replaces); none: the constant below.
  std::optional<AtmosphereParams> atmosphere;
  double density_kg_m3 = 0.0;               // [kg/m³] constant air density without a model, ≥ 0 (0: no drag)
  Eigen::Vector3d disturbance_torque_B_Nm = Eigen::Vector3d::Zero();  // [N m] constant residual torque
  bool gravity_gradient = true;                                       // apply the gravity-gradient torque
  int substeps = 4;                                                   // [-] RK4 substeps per step, ≥ 1
  /// Ideal attitude control: the body axes held on the east–north–zenith frame
  /// (R_N_EastNorthZenith), turning with the orbit; the external torques go
  /// into the wheels, total momentum conserved. For station-keeping runs with
  /// steps far longer than an attitude loop's (seed S3).
  bool attitude_held = false;
  Eigen::Quaterniond q0_NB = Eigen::Quaterniond::Identity();          // initial attitude, unit
  Eigen::Vector3d w0_NB_B_rad_s = Eigen::Vector3d::Zero();            // [rad/s] initial body rate
  Eigen::Vector4d wheel_speed0_rad_s = Eigen::Vector4d::Zero();       // [rad/s] initial speeds relative to body

  /// Every violation as "field: reason", nested ones prefixed ("orbit.eccentricity: …").
  std::vector<std::string> validate() const;
};

}  // namespace flatsat::sim
