// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

#include "sim/Sgp4Elements.hpp"
#include "sim/Sgp4LunarSolar.hpp"
#include "sim/Sgp4Resonance.hpp"
#include "sim/Tle.hpp"

namespace flatsat::sim {

/// SGP4/SDP4 orbit propagation from a TLE: an independent implementation following
/// Vallado, Crawford, Hujsak & Kelso 2006, "Revisiting Spacetrack Report #3"
/// (AIAA 2006-6753) and its reference code, with WGS-72 constants and the improved
/// operation mode ('i'). Orbits with periods of 225 min or more use the deep-space
/// branch (Sgp4LunarSolar, Sgp4Resonance). Times are minutes since the TLE epoch and
/// the output is km and km/s, the units of the model and its verification data.
/// Verified against Vallado's published output (tests/unit/sim/Sgp4Test.cpp).
class Sgp4 {
 public:
  /// Why SGP4 gives no state; the numbers are the error codes of Vallado's code.
  enum class Error {
    kNone = 0,
    kMeanEccentricity = 1,       // mean eccentricity outside [-0.001, 1)
    kMeanMotion = 2,             // mean motion ≤ 0 after the resonance integration
    kPerturbedEccentricity = 3,  // eccentricity after the lunar-solar periodics outside [0, 1]
    kSemiLatusRectum = 4,        // semi-latus rectum < 0
    kDecayed = 6,                // radius below one Earth radius
  };

  /// State in SGP4's units (km, km/s) and frame: TEME, the true equator and mean
  /// equinox of date (see sim/Teme.hpp).
  struct Result {
    Error error = Error::kNone;
    std::string message;       // what went wrong, with the offending value; empty when ok
    Eigen::Vector3d r_T_km;    // [km] position in TEME; NaN on error
    Eigen::Vector3d v_T_km_s;  // [km/s] velocity in TEME; NaN on error

    bool ok() const { return error == Error::kNone; }
  };

  /// @throws std::invalid_argument listing tle.validate()'s violations.
  explicit Sgp4(const Tle& tle);

  /// State at minutes_since_epoch [min] (negative: before the epoch), or the error of
  /// Vallado's code at that time. Const, deterministic and thread-safe: no state
  /// carries over between calls.
  Result propagate(double minutes_since_epoch) const;

  /// [d] Julian date (UTC) of the TLE epoch, whole days (at 0 h) plus the day fraction.
  double epochJulianDate() const { return epoch_jd_ + epoch_jd_fraction_; }

  /// True for the deep-space branch (SDP4): period of 225 min or more.
  bool isDeepSpace() const { return lunar_solar_.has_value(); }

 private:
  /// Near-Earth coefficients (sgp4init outputs; Vallado's names).
  struct Coefficients {
    double bstar = 0.0;
    double aycof = 0.0, xlcof = 0.0, con41 = 0.0, x1mth2 = 0.0, x7thm1 = 0.0;
    double cc1 = 0.0, cc4 = 0.0, cc5 = 0.0, d2 = 0.0, d3 = 0.0, d4 = 0.0, delmo = 0.0, eta = 0.0;
    double omgcof = 0.0, sinmao = 0.0, xmcof = 0.0, nodecf = 0.0;
    double t2cof = 0.0, t3cof = 0.0, t4cof = 0.0, t5cof = 0.0;
    double mdot = 0.0, argpdot = 0.0, nodedot = 0.0;  // [rad/min] secular rates from J2, J4
  };

  double epoch_jd_ = 0.0;           // [d] Julian date of 0 h on the epoch day
  double epoch_jd_fraction_ = 0.0;  // [d] fraction of the day
  Sgp4MeanElements epoch_;          // mean elements at epoch, mean motion un-Kozai'd
  bool simple_drag_ = false;        // Vallado's isimp: perigee below 220 km or deep space
  Coefficients c_;
  std::optional<Sgp4LunarSolar> lunar_solar_;
  std::optional<Sgp4Resonance> resonance_;
};

}  // namespace flatsat::sim
