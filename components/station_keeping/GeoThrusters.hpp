// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <array>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace flatsat::station_keeping {

/// The six ion thrusters on the zenith face of the GEO reference spacecraft,
/// numbered as in the seed (Hughes, JP3299143, Fig. 2 and Table I): the north
/// row NW(20), NC(22), NE(24), the south row SW(26), SC(28), SE(30).
enum class GeoThruster { kNW = 20, kNC = 22, kNE = 24, kSW = 26, kSC = 28, kSE = 30 };

inline constexpr std::array<GeoThruster, 6> kGeoThrusters{GeoThruster::kNW, GeoThruster::kNC, GeoThruster::kNE,
                                                           GeoThruster::kSW, GeoThruster::kSC, GeoThruster::kSE};

/// The power-unit pairs (seed [0030]): 20–30, 22–28, 24–26. One failed
/// thruster takes its pair out; kNone: all six work.
enum class PairFailure { kNone, k22_28, k20_30, k24_26 };

/// Its power-unit partner: 20 <-> 30, 22 <-> 28, 24 <-> 26.
GeoThruster partnerOf(GeoThruster thruster);
/// The pair a failure of `thruster` takes out.
PairFailure failureOf(GeoThruster thruster);
/// False for both thrusters of the failed pair.
bool available(GeoThruster thruster, PairFailure failure);
/// "NW(20)", ...
std::string nameOf(GeoThruster thruster);
/// "nominal", "22/28 failed", ...
std::string nameOf(PairFailure failure);

struct GeoThrusterParams {
  double cant_rad = 0.628;  ///< [rad] θ between each thrust line and the north–south axis, [0.17, 1.4] (seed: 36°)
  double slew_rad = 0.175;  ///< [rad] α about the north–south axis of the outer four, [0, 0.52] (seed: 10–12°)
};

/// Every problem with `params`, naming the field and its range; empty: valid.
std::vector<std::string> validate(const GeoThrusterParams& params);

/// Unit force on the spacecraft of `thruster` in the local orbital frame
/// x east (tangential), y north (orbit normal), z zenith (radial outward).
/// Each thrust line passes through the centre of mass (seed [0011]), so the
/// force points from the thruster's corner of the zenith face to the CM: down
/// (radial toward the Earth, sin θ cos α of it), across the north–south axis
/// (cos θ: the north row pushes south), and, for the outer four, east or west
/// (sin θ sin α: the west thrusters push east). The centre pair NC/SC gives
/// no tangential part.
Eigen::Vector3d forceDirection_orbital(GeoThruster thruster, const GeoThrusterParams& params);

/// The local orbital frame above at the state (r, v) in N: its columns are
/// east (north × zenith), north (along r × v) and zenith (along r), so
/// v_N = R_N_orbital(r, v) · v_orbital.
Eigen::Matrix3d R_N_orbital(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s);

}  // namespace flatsat::station_keeping
