// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim/Geodetic.hpp"
#include "sim/Thrusters.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {

/// Commands held over one step (zero-order hold).
struct ActuatorCommands {
  Eigen::Vector4d wheel_torque_Nm = Eigen::Vector4d::Zero();  // [N m] motor torque on each wheel
  Eigen::Vector3d dipole_B_Am2 = Eigen::Vector3d::Zero();     // [A m²] magnetic torquer dipole, body axes
  double dipole_quiet_fraction = 0.0;  // [-] coils off over this last fraction of the step; outside [0, 1) (or NaN): 0
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
  GeodeticPosition geodetic;                                            // WGS-84 latitude, longitude, height
  Eigen::Vector3d b_N_T = Eigen::Vector3d::Zero();                      // [T] geomagnetic field
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();                      // [T]
  Eigen::Vector3d sun_N_unit = Eigen::Vector3d::Zero();                 // [-] spacecraft → Sun
  Eigen::Vector3d sun_B_unit = Eigen::Vector3d::Zero();                 // [-]
  double illumination = 0.0;                                            // [-] 1 Sun, 0 umbra
  double density_kg_m3 = 0.0;                                           // [kg/m³] air density at the spacecraft
  Eigen::Vector3d dipole_applied_B_Am2 = Eigen::Vector3d::Zero();       // [A m²] after clipping
  Eigen::Vector3d dipole_at_t_B_Am2 = Eigen::Vector3d::Zero();          // [A m²] on at t itself (zero after a quiet part)
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
  Eigen::Vector3d f_flaps_B_N = Eigen::Vector3d::Zero();                // [N] the flaps' share of f_aerodynamic_B_N
  Eigen::Vector3d f_solar_pressure_B_N = Eigen::Vector3d::Zero();       // [N] panels + flaps
  Eigen::Vector3d tau_solar_pressure_B_Nm = Eigen::Vector3d::Zero();    // [N m] panels + flaps
  Eigen::Vector4d flap_angle_applied_rad = Eigen::Vector4d::Zero();     // [rad] after the limits
  Eigen::Vector3d f_thruster_B_N = Eigen::Vector3d::Zero();             // [N] mean over the step
  Eigen::Vector3d tau_thruster_B_Nm = Eigen::Vector3d::Zero();          // [N m] mean over the step
  ThrusterVector thruster_impulse_Ns = ThrusterVector::Zero();          // [N s] delivered per thruster
  ThrusterVector thruster_impulse_total_Ns = ThrusterVector::Zero();    // [N s] delivered per thruster since t = 0
  std::array<std::uint32_t, kMaxThrusters> thruster_burns{};            // [-] burns begun per thruster since t = 0
  ThrusterGimbals thruster_gimbal_applied_rad = ThrusterGimbals::Zero();  // [rad] after the limits
};

}  // namespace flatsat::sim
