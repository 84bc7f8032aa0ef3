// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <Eigen/Core>

namespace flatsat::sim {

// Local frames at a point (besides N inertial and E Earth-fixed):
//   G — geodetic north-east-down: "down" along the inward normal of the WGS-84 ellipsoid;
//   C — geocentric north-east-down: "down" towards the Earth's centre.
// Both take "north" along the meridian of the point's longitude, also at the poles,
// where the longitude given is what fixes the frame (as the WMM and IGRF do).

/// Position on or above the WGS-84 ellipsoid.
struct GeodeticPosition {
  double latitude_rad = 0.0;   // [rad] geodetic latitude φ, [−π/2, π/2]
  double longitude_rad = 0.0;  // [rad] λ, east positive
  double height_m = 0.0;       // [m] h above the ellipsoid, along its normal
};

/// Spherical coordinates about the Earth's centre.
struct GeocentricPosition {
  double radius_m = 0.0;       // [m] r, > 0
  double latitude_rad = 0.0;   // [rad] geocentric latitude φ′, [−π/2, π/2]
  double longitude_rad = 0.0;  // [rad] λ, east positive
};

/// [m] Earth-fixed position of a geodetic point: ((N + h) cos φ cos λ, (N + h) cos φ sin λ,
/// (N (1 − e²) + h) sin φ), N = a / √(1 − e² sin² φ) the prime-vertical radius of
/// curvature (Vallado, Fundamentals of Astrodynamics and Applications, 4th ed., ch. 3).
Eigen::Vector3d earthFixedFromGeodetic(const GeodeticPosition& p);

/// Geodetic point of an Earth-fixed position [m], exact closed form (Heikkinen 1982,
/// as given by Zhu, "Conversion of Earth-centered Earth-fixed coordinates to
/// geodetic coordinates", IEEE Trans. AES 30(3), 1994). Valid more than ~43 km
/// from the Earth's centre, i.e. everywhere a spacecraft or the ground can be.
/// On the polar axis the longitude is 0.
GeodeticPosition geodeticFromEarthFixed(const Eigen::Vector3d& r_E_m);

/// Geocentric spherical coordinates of a geodetic point: r and φ′ of the
/// Earth-fixed position above (the WMM2025 Technical Report's first step, §1.2).
GeocentricPosition geocentricFromGeodetic(const GeodeticPosition& p);

/// Geocentric spherical coordinates of an Earth-fixed position [m] (≠ 0); on the
/// polar axis the longitude is 0.
GeocentricPosition geocentricFromEarthFixed(const Eigen::Vector3d& r_E_m);

/// Rotation from the geodetic NED frame G at p to E: v_E = R_EG * v_G.
Eigen::Matrix3d R_EG(const GeodeticPosition& p);

/// Rotation from the geocentric NED frame C at p to E: v_E = R_EC * v_C.
Eigen::Matrix3d R_EC(const GeocentricPosition& p);

/// Rotation from the geocentric NED frame C to the geodetic NED frame G at the
/// same point: a turn about east by φ′ − φ, X = X′ cos(φ′ − φ) − Z′ sin(φ′ − φ),
/// Z = X′ sin(φ′ − φ) + Z′ cos(φ′ − φ) (WMM2025 Technical Report, §1.2).
Eigen::Matrix3d R_GC(double geodetic_latitude_rad, double geocentric_latitude_rad);

}  // namespace flatsat::sim
