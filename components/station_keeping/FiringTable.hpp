// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <vector>

#include <Eigen/Dense>

#include "components/station_keeping/GeoThrusters.hpp"

namespace flatsat::station_keeping {

/// What a firing is for (the seed's Table I): i inclination, d east–west
/// drift (mean motion), e eccentricity, MD momentum dumping by gimbal offset.
enum class Job { kInclinationDriftEccentricity, kMomentumDump, kInclinationAndDump, kDriftAndEccentricity };

/// Table I gives the firing momentum dumping: MD alone, or i and MD.
inline bool dumpsMomentum(Job job) { return job == Job::kMomentumDump || job == Job::kInclinationAndDump; }

/// Where in the year the Sun is, as the table needs it.
struct Season {
  /// Winter/spring: from the December to the June solstice (cos RA_sun > 0);
  /// else summer/autumn.
  bool winter_spring = true;
  enum class Eclipse { kNone, kSpring, kAutumn };
  /// An eclipse season: the Earth's shadow, penumbra included, reaches the
  /// equatorial orbit, |δ_sun| < asin(R_E / r) + the Sun's angular radius
  /// (9.0° at GEO: about 45 days around each equinox, seed [0030]).
  Eclipse eclipse = Eclipse::kNone;
};

/// The season for the Sun's direction `sun_N_unit` (inertial, equator and
/// equinox) seen from an equatorial orbit of radius `orbit_radius_m`; the
/// eclipse seasons widened by `margin_rad` of solar declination (a plan made
/// now fires up to an orbit later, when the Sun has moved up to 0.4°).
Season seasonOf(const Eigen::Vector3d& sun_N_unit, double orbit_radius_m, double margin_rad = 0.0);

/// [rad] The right ascension of `angle_rad`, in [0, 2π).
double wrapRa(double angle_rad);

/// One firing per orbit: `thruster` at right ascension `ra_rad` (from the
/// vernal equinox, [0, 2π)) for `job`.
struct Firing {
  GeoThruster thruster = GeoThruster::kNW;
  double ra_rad = 0.0;  ///< [rad] right ascension of the spacecraft at the firing's centre
  Job job = Job::kInclinationDriftEccentricity;
};

/// The seed's Table I (Hughes, JP3299143): which thrusters fire where in the
/// orbit, for each state and season. `sun_ra_rad` is the Sun's right
/// ascension (for the "RA_sun + 180°" rows).
///
/// One reading of the table: in the 20/30 and 24/26 failures the centre pair
/// 22/28 keeps firing for i and MD in the eclipse seasons too. There the d/e
/// firings move to RA 90°/270° and couple into the inclination, in autumn
/// against it; the seed offsets that coupling with 22/28 ("predicted and
/// offset by equalizing the firing of the thrusters 22 and 28"), and
/// 90°/270° are never in the shadow.
std::vector<Firing> firingsFor(PairFailure failure, const Season& season, double sun_ra_rad);

}  // namespace flatsat::station_keeping
