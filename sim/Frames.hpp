// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <Eigen/Core>

namespace flatsat::sim {

// Rotation matrices are named R_<to><from>: v_N = R_N_X * v_X, so the columns of
// R_N_X are the axes of frame X written in the inertial frame N.

/// [rad] Earth rotation angle θ in [0, 2π) between the celestial and terrestrial
/// intermediate origins (IERS Conventions 2010, Eq. 5.15).
double earthRotationAngle_rad(double jd_ut1);

/// [rad] Mean obliquity of the ecliptic of date, IAU 1976 (Lieske et al. 1977; Vallado Eq. 3-68).
double meanObliquity_rad(double jd_tt);

/// Radial / along-track / cross-track frame RSW (Vallado §3.3): x = R = r/|r|
/// (radial, outward), z = W = (r × v)/|r × v| (orbit normal), y = S = W × R
/// (along-track, the velocity direction on a circular orbit). r and v not parallel.
Eigen::Matrix3d R_N_RSW(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s);

/// Local-vertical / local-horizontal frame of attitude control (nadir pointing;
/// Markley & Crassidis, Fundamentals of Spacecraft Attitude Determination and
/// Control, 2014, Ch. 2): z = −r/|r| (nadir), y = −(r × v)/|r × v| (negative orbit
/// normal), x = y × z (along-track, the velocity direction on a circular orbit).
/// The same axes as RSW, relabelled: x_LVLH = S, y_LVLH = −W, z_LVLH = −R.
Eigen::Matrix3d R_N_LVLH(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s);

/// Orbital frame of seed S3's geostationary spacecraft (JP3299143; the thrusters'
/// frame of components/station_keeping/GeoThrusters.hpp): x east (along-track S),
/// y north (orbit normal W), z zenith (R): RSW relabelled. The frame turns with the
/// orbit, at (r × v)/|r|².
Eigen::Matrix3d R_N_EastNorthZenith(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s);

/// Orbital frame of seed S2 (CNES FR2718105, Fig. 2; sim/Flaps.hpp): roll x along the
/// track against the motion, yaw z away from the Earth's centre, pitch y = z × x
/// (negative orbit normal): LVLH turned by 180° about its y axis. The frame turns with
/// the orbit, at (r × v)/|r|².
Eigen::Matrix3d R_N_S2Orbital(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s);

/// Sun-ecliptic reference frame of seed S0 (algorithms.md): X = Sun direction (the
/// body x axis when Sun pointing), Y parallel to the ecliptic of date (towards the
/// Sun's apparent motion), Z = X × Y normal to the ecliptic (towards its north pole).
/// @param sun_N_unit [-] unit vector towards the Sun; it lies in the ecliptic up to
///        the satellite's parallax (< 0.01°), so Z is the ecliptic pole to that accuracy.
/// @param jd_tt [d] Julian date, terrestrial time (fixes the obliquity).
Eigen::Matrix3d R_N_SunEcliptic(const Eigen::Vector3d& sun_N_unit, double jd_tt);

}  // namespace flatsat::sim
