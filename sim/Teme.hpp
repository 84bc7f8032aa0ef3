// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <Eigen/Core>

namespace flatsat::sim {

/// Rotation from TEME (T: true equator, mean equinox of date, the frame of SGP4's
/// output) to the pseudo-Earth-fixed frame (E): v_E = R_ET * v_T, a rotation about z by
/// the Greenwich mean sidereal time (gmst_rad, IAU-82), as Vallado, Crawford, Hujsak &
/// Kelso 2006 (AIAA 2006-6753) define TEME. Polar motion is ignored (PEF ≈ ITRF, ~10 m
/// at the surface) and UTC is used for UT1 (|UT1 − UTC| < 0.9 s, i.e. < 0.4 km of
/// Earth-fixed position at the equator).
/// @param jd_ut1 [d] Julian date (UT1, or UTC within the above).
Eigen::Matrix3d R_ET(double jd_ut1);

/// Rotation from TEME (T) to the rig's inertial frame N: v_N = R_NT * v_T, formed
/// through the Earth-fixed frame as R_EN(jd)ᵀ · R_ET(jd), which is how TEME is meant to
/// be converted (Vallado et al. 2006). The rig's N is defined by R_EN = Rz(GMST), the
/// same rotation, so today R_NT is the identity (up to rounding): N *is* TEME, and the
/// difference between TEME and mean-of-date or J2000 axes (nutation, tens of arcsec;
/// precession, ~50"/yr since 2000, ~0.35° in 2025) is the rig's documented inertial-
/// frame approximation. Written as a composition so that it stays right when R_EN
/// gains precession and nutation.
/// @param jd_ut1 [d] Julian date (UT1, or UTC as for R_ET).
Eigen::Matrix3d R_NT(double jd_ut1);

}  // namespace flatsat::sim
