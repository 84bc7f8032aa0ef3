// SPDX-License-Identifier: Apache-2.0
#include "components/station_keeping/FiringTable.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/Constants.hpp"

namespace flatsat::station_keeping {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

using T = GeoThruster;

/// The rows of one failure of an outer pair: 22/28 for i and MD; `pair` (the
/// two outer thrusters left on opposite corners) for d and e, at RA_sun + 180°
/// outside the eclipse seasons, where the unpaired radial ΔV is wanted against
/// the Sun-driven eccentricity, and at 90°/270° inside them.
std::vector<Firing> outerPairFailed(T north, T south, bool north_at_90_in_spring, const Season& season,
                                    double sun_ra_rad) {
  std::vector<Firing> firings{{T::kNC, 90.0 * kDeg, Job::kInclinationAndDump},
                              {T::kSC, 270.0 * kDeg, Job::kInclinationAndDump}};
  const auto de = Job::kDriftAndEccentricity;
  switch (season.eclipse) {
    case Season::Eclipse::kNone:
      firings.push_back({north, wrapRa(sun_ra_rad + std::numbers::pi), de});
      firings.push_back({south, wrapRa(sun_ra_rad + std::numbers::pi), de});
      break;
    case Season::Eclipse::kSpring:
    case Season::Eclipse::kAutumn: {
      const bool north_at_90 = north_at_90_in_spring == (season.eclipse == Season::Eclipse::kSpring);
      firings.push_back({north, (north_at_90 ? 90.0 : 270.0) * kDeg, de});
      firings.push_back({south, (north_at_90 ? 270.0 : 90.0) * kDeg, de});
      break;
    }
  }
  return firings;
}

}  // namespace

double wrapRa(double angle_rad) {
  const double wrapped = std::fmod(angle_rad, 2.0 * std::numbers::pi);
  return wrapped < 0.0 ? wrapped + 2.0 * std::numbers::pi : wrapped;
}

Season seasonOf(const Eigen::Vector3d& sun_N_unit, double orbit_radius_m, double margin_rad) {
  Season season;
  season.winter_spring = sun_N_unit.x() > 0.0;
  const double declination = std::asin(std::clamp(sun_N_unit.z(), -1.0, 1.0));
  // The penumbra reaches the Sun's angular radius further than the umbra.
  const double reach = std::asin(sim::kEarthEquatorialRadius_m / orbit_radius_m) +
                       std::asin(sim::kSunRadius_m / sim::kAstronomicalUnit_m) + margin_rad;
  if (std::abs(declination) < reach) {
    season.eclipse = season.winter_spring ? Season::Eclipse::kSpring : Season::Eclipse::kAutumn;
  }
  return season;
}

std::vector<Firing> firingsFor(PairFailure failure, const Season& season, double sun_ra_rad) {
  switch (failure) {
    case PairFailure::kNone: {
      const auto ide = Job::kInclinationDriftEccentricity;
      return {{T::kNW, 90.0 * kDeg, ide},  {T::kNE, 90.0 * kDeg, ide},
              {T::kSW, 270.0 * kDeg, ide}, {T::kSE, 270.0 * kDeg, ide},
              {T::kNC, 90.0 * kDeg, Job::kMomentumDump}, {T::kSC, 270.0 * kDeg, Job::kMomentumDump}};
    }
    case PairFailure::k22_28:
      // The outer pairs alternate every six months so that none fires in the
      // shadow (seed [0030]): the d/e firings sit opposite the equinox's eclipse.
      if (season.winter_spring) {
        return {{T::kNE, 90.0 * kDeg, Job::kInclinationAndDump},
                {T::kSW, 270.0 * kDeg, Job::kInclinationAndDump},
                {T::kNE, 0.0, Job::kDriftAndEccentricity},
                {T::kSW, 0.0, Job::kDriftAndEccentricity}};
      }
      return {{T::kNW, 90.0 * kDeg, Job::kInclinationAndDump},
              {T::kSE, 270.0 * kDeg, Job::kInclinationAndDump},
              {T::kNW, 180.0 * kDeg, Job::kDriftAndEccentricity},
              {T::kSE, 180.0 * kDeg, Job::kDriftAndEccentricity}};
    case PairFailure::k20_30:
      return outerPairFailed(T::kNE, T::kSW, /*north_at_90_in_spring=*/true, season, sun_ra_rad);
    case PairFailure::k24_26:
      return outerPairFailed(T::kNW, T::kSE, /*north_at_90_in_spring=*/false, season, sun_ra_rad);
  }
  return {};
}

}  // namespace flatsat::station_keeping
