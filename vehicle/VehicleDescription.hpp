// SPDX-License-Identifier: Apache-2.0
#pragma once
// One spacecraft as the scenario describes it: what the dynamics server
// builds its truth plant from, and what flight software knows of it (the
// onboard view, equal to the truth unless the scenario's `onboard:` section
// says otherwise). Pure: Eigen + std + sim types.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim/ActuatorFaults.hpp"
#include "sim/Atmosphere.hpp"
#include "sim/Flaps.hpp"
#include "sim/GeomagneticCoefficients.hpp"
#include "sim/GeomagneticField.hpp"
#include "sim/SpotFieldModel.hpp"
#include "sim/KeplerOrbit.hpp"
#include "sim/OrbitTrack.hpp"
#include "sim/PanelModel.hpp"
#include "sim/RigidBodyWheels.hpp"
#include "sim/Thrusters.hpp"
#include "sim/Time.hpp"

namespace flatsat::vehicle {

/// How each sensor head sits on the body.
struct SensorMountings {
  Eigen::Vector3d sun_sensor_boresight_B = Eigen::Vector3d::UnitX();  ///< [-] unit, body axes
  Eigen::Quaterniond q_body_star_tracker = Eigen::Quaterniond::Identity();  ///< [-] unit, sensor → body; boresight sensor +z
  Eigen::Quaterniond q_body_magnetometer = Eigen::Quaterniond::Identity();  ///< [-] unit, sensor → body

  /// Every violation as "field: reason".
  std::vector<std::string> validate() const;
};

/// A geomagnetic field model: the environment's for the truth, the one the
/// onboard computer carries for the onboard view.
struct FieldModel {
  bool spherical_harmonics = false;   ///< false: the tilted dipole (IGRF degree 1)
  sim::DipoleCoefficients dipole;     ///< [nT] degree-1 coefficients at the epoch's year (always loaded)
  sim::GaussCoefficients harmonics;   ///< [nT] spherical_harmonics: IGRF-14 or WMM2025 at the epoch's decimal year
  int degree = sim::GaussCoefficients::kMaxDegree;  ///< [-] spherical_harmonics: highest degree used, 1..13
  /// Onboard only (`onboard.field_model: spot`): seed S2's field along the orbit (claim 5),
  /// its first harmonic (B0 from the dipole's g10) or, with `onboard.spot_harmonics: odd`,
  /// harmonics 1, 3 and 5 of IGRF's zonal part; it replaces the models above.
  std::optional<sim::SpotFieldModel> spot;

  std::vector<std::string> validate() const;
};

/// Epoch, orbit, mass properties, actuators, sensor mountings and the
/// models of the space around the spacecraft that flight software carries.
struct VehicleDescription {
  sim::UtcEpoch epoch;                  ///< scenario epoch (t = 0), UTC; UT1 taken equal to UTC
  sim::OrbitElements orbit;             ///< osculating elements at the epoch, inertial frame N = ECI
  sim::OrbitTrackParams orbit_track;    ///< Kepler or numerical (forces, mass, areas, step)
  /// [rad] east of Greenwich, [−π, π]: the geostationary slot (orbit.station_longitude_deg),
  /// where the satellite starts and station keeping holds it; none for other orbits.
  std::optional<double> station_longitude_rad;
  FieldModel field;
  /// Density model of the panels' drag and the numerical orbit's drag; none: density_kg_m3.
  std::optional<sim::AtmosphereParams> atmosphere;
  double density_kg_m3 = 0.0;           ///< [kg/m³] constant density without a model, ≥ 0 (0: no drag)
  sim::RigidBodyParams body;            ///< inertia and reaction wheels (with friction)
  Eigen::Vector3d torquer_max_dipole_Am2 = Eigen::Vector3d::Zero();  ///< [A m²] per coil (body x, y, z), ≥ 0
  Eigen::Vector3d residual_dipole_B_Am2 = Eigen::Vector3d::Zero();   ///< [A m²] the spacecraft's own dipole
  std::vector<sim::Panel> panels;               ///< drag and solar-pressure surfaces; none by default
  std::vector<sim::ThrusterParams> thrusters;   ///< at most sim::kMaxThrusters
  sim::FlapsParams flaps;                       ///< seed S2 flaps; not fitted by default
  SensorMountings sensors;
  /// Timed actuator failures: for the truth, what the plant suffers; onboard,
  /// what fault management has declared (the same unless `onboard.faults` says otherwise).
  std::vector<sim::ActuatorFault> faults;

  /// Every violation as "field: reason", nested ones prefixed ("body.J_B_kg_m2: …").
  std::vector<std::string> validate() const;
};

/// The spacecraft twice: as it is, and as flight software believes it is.
/// Emulators and the dynamics server read `truth`; flight components read
/// only `onboard`.
struct Vehicle {
  VehicleDescription truth;
  VehicleDescription onboard;
};

}  // namespace flatsat::vehicle
