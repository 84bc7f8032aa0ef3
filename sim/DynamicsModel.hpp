// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim/Atmosphere.hpp"
#include "sim/DynamicsParams.hpp"
#include "sim/Flaps.hpp"
#include "sim/GeomagneticField.hpp"
#include "sim/OrbitTrack.hpp"
#include "sim/PanelModel.hpp"
#include "sim/RigidBodyWheels.hpp"
#include "sim/SphericalHarmonicField.hpp"
#include "sim/Thrusters.hpp"
#include "sim/Truth.hpp"

namespace flatsat::sim {

/// Orbit, attitude, wheels and environment of one spacecraft; the pure core of
/// the dynamics server. Deterministic: same params and commands → identical truth.
///
/// Frames: N = ECI; Earth-fixed E = R_EN(JD_UT1) N with UT1 ≈ UTC; the Sun is
/// evaluated at TT = UTC + kTtMinusUtc_s. The field model (tilted dipole or
/// spherical harmonics) is built once, with its coefficients at the epoch's
/// decimal year: the secular variation (IGRF-14 2026: ≤ 217 nT/yr at the ground,
/// ≤ 146 nT/yr at 560 km) moves the field by < 0.6 nT per day of run, below a
/// magnetometer's noise.
///
/// The environment (orbit, field, Sun, shadow, density, wind) is evaluated at the
/// end of every step and interpolated linearly between the step's ends for the
/// RK4 stages: over a 0.1 s step the field and the position turn by ~2e-4 rad, so
/// the chord differs from the curve by ~(2e-4)²/8 ≈ 5e-9 relative — far below the
/// models' accuracy, for one field evaluation per step instead of 4 per substep.
///
/// The external torque at each RK4 stage, with that stage's attitude: gravity
/// gradient (if enabled) + (torquer + residual dipole) × b_B + aerodynamic and
/// solar-pressure torques of the panels and flaps + the constant disturbance + the
/// thrusters' mean torque over the step. The air co-rotates with the Earth
/// (wind = −(v − ω_E × r)); its density is the atmosphere model's, or constant.
/// The numerical orbit (OrbitTrack) also takes the thrusters' mean force over the
/// step, as a constant acceleration a = R_NB f / m applied at the step's end:
/// Δr = ½ a dt², Δv = a dt (R_NB the mean of the step's end attitudes). The
/// Kepler orbit ignores thrust; panel forces act on the attitude only (the
/// numerical orbit's drag and solar pressure use its own cannonball areas).
class DynamicsModel {
 public:
  /// @throws std::invalid_argument listing every DynamicsParams::validate() error.
  explicit DynamicsModel(const DynamicsParams& params);

  /// Back to the initial state at t = 0.
  void reset();

  /// Truth at the current time.
  const Truth& truth() const { return truth_; }

  /// Holds cmd over [t_now, t_next) — wheel torque saturated at the start of the
  /// interval, dipole clipped per coil, flap and gimbal angles limited, thruster
  /// pulses cut to the step — integrates to t_next and recomputes the truth.
  /// A t_next not after t_now changes nothing. Never throws, never allocates.
  void step(const ActuatorCommands& cmd, SimTime t_next);
  /// How many coil and wheel commands of the last step() were beyond their
  /// actuator's limit and held to it (a value that is not finite counts too).
  std::uint32_t commandsClamped() const { return commands_clamped_; }

 private:
  struct Environment {
    KeplerOrbit::State orbit;
    Eigen::Vector3d r_E_m;       // Earth-fixed position
    Eigen::Vector3d b_N_T;
    Eigen::Vector3d wind_N_m_s;  // air relative to the spacecraft
    Eigen::Vector3d r_sun_N_m;   // Sun from the Earth's centre
    double illumination;
    double solar_flux_W_m2;
    double density_kg_m3;
  };
  struct Torques {
    Eigen::Vector3d gravity_gradient_B_Nm;
    Eigen::Vector3d magnetic_B_Nm;
    Eigen::Vector3d residual_magnetic_B_Nm;
    ForceTorque aerodynamic;  // panels + flaps
    ForceTorque flaps_aerodynamic;
    ForceTorque solar_pressure;
    Eigen::Vector3d b_B_T;
    Eigen::Vector3d wind_B_m_s;
    Eigen::Vector3d sun_B_unit;

    Eigen::Vector3d total_B_Nm() const;
  };
  /// What the actuators do over one step, held from its start.
  struct Applied {
    Eigen::Vector4d wheel_torque_Nm = Eigen::Vector4d::Zero();
    Eigen::Vector3d dipole_B_Am2 = Eigen::Vector3d::Zero();
    double dipole_on_fraction = 1.0;  // [-] of the step, from its start
    Eigen::Vector4d flap_angle_rad = Eigen::Vector4d::Zero();
    ThrusterOutput thrusters;
  };

  /// Advances the orbit to t_s (never back).
  Environment environmentAt(double t_s);
  /// attitude_held: the body on the east–north–zenith frame of `orbit`, the
  /// wheels holding the rest of H_N_Nms.
  RigidBodyState heldState(const KeplerOrbit::State& orbit, const Eigen::Vector3d& H_N_Nms) const;
  /// The chord from a (s = 0) to b (s = 1).
  static Environment interpolated(const Environment& a, const Environment& b, double s);
  Torques torquesAt(const Environment& env, const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& dipole_B_Am2) const;
  /// The torques that only the attitude and the environment decide: gravity
  /// gradient, residual dipole, and the body panels' drag and solar pressure
  /// (not the torquers, not the flaps, whose angles change from step to step).
  Torques attitudeTorquesAt(const Environment& env, const Eigen::Quaterniond& q_NB) const;
  Eigen::Vector3d clipDipole(const Eigen::Vector3d& dipole_B_Am2) const;
  std::uint32_t commandsBeyondLimits(const ActuatorCommands& cmd) const;
  std::uint32_t commands_clamped_ = 0;  // by the last step()
  void setFlaps(const Eigen::Vector4d& flap_angle_rad);
  void updateTruth(const Applied& applied, double substep_s);

  DynamicsParams params_;
  OrbitTrack orbit_;
  RigidBodyWheels body_;
  TiltedDipoleField dipole_;
  std::optional<SphericalHarmonicField> harmonics_;  // FieldModel::kSphericalHarmonics
  std::optional<Atmosphere> atmosphere_;             // none: constant density
  Thrusters thrusters_;
  std::optional<Flaps> flaps_;
  std::array<Panel, kFlapPanelCount> flap_panels_;  // faces at the angles held over the step
  double jd_epoch_;  // [d] Julian date of t = 0, UTC ≈ UT1
  SimTime t_ = 0;
  RigidBodyState state_;
  Environment env_;  // at t_
  /// attitudeTorquesAt(env_, q_NB) of the truth. The next step's first RK4
  /// stage is at the same attitude and environment: it takes them instead of
  /// summing the panels again, one evaluation of the five a step.
  struct AttitudeTorques {
    Eigen::Quaterniond q_NB;
    Torques torques;
  };
  std::optional<AttitudeTorques> truth_torques_;
  Truth truth_;
};

}  // namespace flatsat::sim
