// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim/Flaps.hpp"
#include "sim/GeomagneticField.hpp"
#include "sim/KeplerOrbit.hpp"
#include "sim/PanelModel.hpp"
#include "sim/RigidBodyWheels.hpp"
#include "sim/Thrusters.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {

/// [s] TT − UTC = 32.184 s + 37 leap seconds (valid since 2017-01-01).
inline constexpr double kTtMinusUtc_s = 69.184;

struct DynamicsParams {
  UtcEpoch epoch;            // scenario epoch (t = 0), UTC; UT1 taken equal to UTC
  OrbitElements orbit;       // Kepler elements at the epoch, inertial frame N = ECI
  RigidBodyParams body;      // inertia and reaction wheels (with friction)
  DipoleCoefficients field;  // [nT] degree-1 IGRF coefficients for the scenario's year
  Eigen::Vector3d torquer_max_dipole_Am2 = Eigen::Vector3d::Zero();   // [A m²] per coil (body x, y, z), ≥ 0
  Eigen::Vector3d residual_dipole_B_Am2 = Eigen::Vector3d::Zero();    // [A m²] spacecraft's own dipole, always on
  std::vector<Panel> panels;                // surface model for drag and solar pressure; none by default
  std::vector<ThrusterParams> thrusters;    // at most kMaxThrusters; none by default
  FlapsParams flaps;                        // seed S2 flaps; not fitted by default
  double density_kg_m3 = 0.0;               // [kg/m³] air density, constant, ≥ 0 (0: no drag)
  Eigen::Vector3d disturbance_torque_B_Nm = Eigen::Vector3d::Zero();  // [N m] constant residual torque
  bool gravity_gradient = true;                                       // apply the gravity-gradient torque
  int substeps = 4;                                                   // [-] RK4 substeps per step, ≥ 1
  Eigen::Quaterniond q0_NB = Eigen::Quaterniond::Identity();          // initial attitude, unit
  Eigen::Vector3d w0_NB_B_rad_s = Eigen::Vector3d::Zero();            // [rad/s] initial body rate
  Eigen::Vector4d wheel_speed0_rad_s = Eigen::Vector4d::Zero();       // [rad/s] initial speeds relative to body

  /// Every violation as "field: reason", nested ones prefixed ("orbit.eccentricity: …").
  std::vector<std::string> validate() const;
};

/// Commands held over one step (zero-order hold).
struct ActuatorCommands {
  Eigen::Vector4d wheel_torque_Nm = Eigen::Vector4d::Zero();  // [N m] motor torque on each wheel
  Eigen::Vector3d dipole_B_Am2 = Eigen::Vector3d::Zero();     // [A m²] magnetic torquer dipole, body axes
  ThrusterVector thruster_on_time_s = ThrusterVector::Zero();  // [s] on-time of each thruster within the step
  ThrusterGimbals thruster_gimbal_rad = ThrusterGimbals::Zero();  // [rad] gimbal angles (1, 2) per thruster
  Eigen::Vector4d flap_angle_rad = Eigen::Vector4d::Zero();   // [rad] θ1..θ4 of the S2 flaps (Flaps.hpp)
};

/// True state and environment at time t. The applied actuator values are those
/// held over the step that ended at t (zero after reset()).
struct Truth {
  SimTime t = 0;                                                        // [ns] since epoch
  Eigen::Quaterniond q_NB = Eigen::Quaterniond::Identity();             // body → inertial
  Eigen::Vector3d w_NB_B_rad_s = Eigen::Vector3d::Zero();               // [rad/s]
  Eigen::Vector4d wheel_speed_rad_s = Eigen::Vector4d::Zero();          // [rad/s] relative to body
  Eigen::Vector4d wheel_torque_applied_Nm = Eigen::Vector4d::Zero();    // [N m] after saturation
  Eigen::Vector3d h_wheels_B_Nms = Eigen::Vector3d::Zero();             // [N m s] Σ a_i I_w Ω_i
  Eigen::Vector3d H_total_N_Nms = Eigen::Vector3d::Zero();              // [N m s] body + wheels, inertial
  Eigen::Vector3d r_N_m = Eigen::Vector3d::Zero();                      // [m] position
  Eigen::Vector3d v_N_m_s = Eigen::Vector3d::Zero();                    // [m/s] velocity
  Eigen::Vector3d b_N_T = Eigen::Vector3d::Zero();                      // [T] geomagnetic field
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();                      // [T]
  Eigen::Vector3d sun_N_unit = Eigen::Vector3d::Zero();                 // [-] spacecraft → Sun
  Eigen::Vector3d sun_B_unit = Eigen::Vector3d::Zero();                 // [-]
  double illumination = 0.0;                                            // [-] 1 Sun, 0 umbra
  Eigen::Vector3d dipole_applied_B_Am2 = Eigen::Vector3d::Zero();       // [A m²] after clipping
  Eigen::Vector3d tau_gravity_gradient_B_Nm = Eigen::Vector3d::Zero();  // [N m]
  Eigen::Vector3d tau_magnetic_B_Nm = Eigen::Vector3d::Zero();          // [N m] dipole × b_B
  Eigen::Vector3d tau_disturbance_B_Nm = Eigen::Vector3d::Zero();       // [N m] constant residual
  Eigen::Vector3d tau_residual_magnetic_B_Nm = Eigen::Vector3d::Zero(); // [N m] residual dipole × b_B
  Eigen::Vector4d wheel_friction_torque_Nm = Eigen::Vector4d::Zero();   // [N m] bearing friction on each rotor
  Eigen::Vector3d wind_B_m_s = Eigen::Vector3d::Zero();                 // [m/s] air relative to the spacecraft
  double solar_flux_W_m2 = 0.0;                                         // [W/m²] at the spacecraft, shadow included
  Eigen::Vector3d f_aerodynamic_B_N = Eigen::Vector3d::Zero();          // [N] panels + flaps
  Eigen::Vector3d tau_aerodynamic_B_Nm = Eigen::Vector3d::Zero();       // [N m] panels + flaps
  Eigen::Vector3d tau_flaps_B_Nm = Eigen::Vector3d::Zero();             // [N m] the flaps' share of the above
  Eigen::Vector3d f_solar_pressure_B_N = Eigen::Vector3d::Zero();       // [N] panels + flaps
  Eigen::Vector3d tau_solar_pressure_B_Nm = Eigen::Vector3d::Zero();    // [N m] panels + flaps
  Eigen::Vector4d flap_angle_applied_rad = Eigen::Vector4d::Zero();     // [rad] after the limits
  Eigen::Vector3d f_thruster_B_N = Eigen::Vector3d::Zero();             // [N] mean over the step
  Eigen::Vector3d tau_thruster_B_Nm = Eigen::Vector3d::Zero();          // [N m] mean over the step
  ThrusterVector thruster_impulse_Ns = ThrusterVector::Zero();          // [N s] delivered per thruster
  ThrusterGimbals thruster_gimbal_applied_rad = ThrusterGimbals::Zero();  // [rad] after the limits
};

/// Orbit, attitude, wheels and environment of one spacecraft; the pure core of
/// the dynamics server. Deterministic: same params and commands → identical truth.
/// Frames: N = ECI; Earth-fixed E = R_EN(JD_UT1) N with UT1 ≈ UTC; the Sun is
/// evaluated at TT = UTC + kTtMinusUtc_s. The external torque is re-evaluated at
/// every RK4 stage with that stage's time and attitude: gravity gradient (if
/// enabled) + (torquer + residual dipole) × b_B + aerodynamic and solar pressure
/// torques of the panels and flaps + the constant disturbance + the thrusters'
/// mean torque over the step. The air co-rotates with the Earth (wind =
/// −(v − ω_E × r)). Forces are reported but do not act on the orbit, which stays
/// Keplerian.
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

 private:
  struct Environment {
    KeplerOrbit::State orbit;
    Eigen::Vector3d b_N_T;
    Eigen::Vector3d wind_N_m_s;  // air relative to the spacecraft
    Eigen::Vector3d r_sun_N_m;   // Sun from the Earth's centre
    double illumination;
    double solar_flux_W_m2;
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
    Eigen::Vector4d flap_angle_rad = Eigen::Vector4d::Zero();
    ThrusterOutput thrusters;
  };

  Environment environmentAt(double t_s) const;
  Torques torquesAt(const Environment& env, const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& dipole_B_Am2) const;
  Eigen::Vector3d clipDipole(const Eigen::Vector3d& dipole_B_Am2) const;
  void setFlaps(const Eigen::Vector4d& flap_angle_rad);
  void updateTruth(const Applied& applied, double substep_s);

  DynamicsParams params_;
  KeplerOrbit orbit_;
  RigidBodyWheels body_;
  TiltedDipoleField field_;
  Thrusters thrusters_;
  std::optional<Flaps> flaps_;
  std::array<Panel, kFlapPanelCount> flap_panels_;  // faces at the angles held over the step
  double jd_epoch_;  // [d] Julian date of t = 0, UTC ≈ UT1
  SimTime t_ = 0;
  RigidBodyState state_;
  Truth truth_;
};

}  // namespace flatsat::sim
