// SPDX-License-Identifier: Apache-2.0
#pragma once

#include "sim/Sgp4Elements.hpp"

namespace flatsat::sim {

/// Lunar and solar third-body perturbations of SDP4, the deep-space branch of SGP4
/// (periods ≥ 225 min): secular rates and long-period periodics of the mean elements.
/// Follows Vallado, Crawford, Hujsak & Kelso 2006 (AIAA 2006-6753), procedures dscom,
/// dsinit (third-body part) and dpper of its reference code, which restate the DEEP
/// routine of Hoots & Roehrich 1980 (Spacetrack Report #3) and Hoots 1986 (STR #6).
/// Variable names follow that code so each line can be checked against it.
class Sgp4LunarSolar {
 public:
  /// Secular rates of the mean elements from the Sun and the Moon.
  struct Rates {
    double dedt = 0.0;   // [1/min] eccentricity
    double didt = 0.0;   // [rad/min] inclination
    double dmdt = 0.0;   // [rad/min] mean anomaly
    double domdt = 0.0;  // [rad/min] argument of perigee
    double dnodt = 0.0;  // [rad/min] node
  };

  /// @param epoch_days_1950 [d] epoch in days since 1950 January 0.0 UTC (SGP4's epoch).
  /// @param epoch mean elements at epoch, mean motion un-Kozai'd [rad/min].
  Sgp4LunarSolar(double epoch_days_1950, const Sgp4MeanElements& epoch);

  const Rates& rates() const { return rates_; }

  /// Adds the secular drift over t_min [min] since epoch to e, i, ω, Ω and M (dspace).
  void applySecular(double t_min, Sgp4MeanElements& m) const;

  /// Adds the long-period periodics at t_min [min] to e, i, Ω, ω and M (dpper, improved
  /// mode, Lyddane's modification below 0.2 rad of perturbed inclination). Mean motion
  /// is unchanged.
  void applyPeriodics(double t_min, Sgp4MeanElements& m) const;

 private:
  /// Solar (s*) and lunar (x*, e*) periodic coefficients and the mean anomalies of
  /// the Moon (zmol) and the Sun (zmos) at epoch [rad] (dscom outputs).
  struct Periodics {
    double e3, ee2, se2, se3, sgh2, sgh3, sgh4, sh2, sh3, si2, si3, sl2, sl3, sl4;
    double xgh2, xgh3, xgh4, xh2, xh3, xi2, xi3, xl2, xl3, xl4;
    double zmol, zmos;
  };

  Rates rates_;
  Periodics p_;
};

}  // namespace flatsat::sim
