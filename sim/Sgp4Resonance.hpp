// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <optional>

#include "sim/Sgp4Elements.hpp"
#include "sim/Sgp4LunarSolar.hpp"

namespace flatsat::sim {

/// Earth-gravity resonance of SDP4: tesseral harmonics that do not average out when
/// the period is near one day (geosynchronous) or half a day with e ≥ 0.5 (Molniya).
/// The resonant mean motion and longitude are integrated numerically from epoch.
/// Follows Vallado, Crawford, Hujsak & Kelso 2006 (AIAA 2006-6753), procedures dsinit
/// (resonance part) and dspace of its reference code, after Hoots & Roehrich 1980
/// (Spacetrack Report #3, DEEP) with Vallado's fixes for negative times.
/// Variable names follow that code so each line can be checked against it.
class Sgp4Resonance {
 public:
  /// What the resonance terms need at epoch.
  struct Epoch {
    Sgp4MeanElements elements;  // mean elements at epoch, mean motion un-Kozai'd [rad/min]
    double mdot = 0.0;          // [rad/min] secular rate of M from J2, J4 (sgp4init)
    double argpdot = 0.0;       // [rad/min] secular rate of ω
    double nodedot = 0.0;       // [rad/min] secular rate of Ω
    double gsto = 0.0;          // [rad] Greenwich mean sidereal time at epoch, [0, 2π)
  };

  /// The resonance of an orbit, or nothing when its mean motion is near neither
  /// resonance (Vallado's irez = 0).
  static std::optional<Sgp4Resonance> of(const Epoch& epoch, const Sgp4LunarSolar::Rates& lunar_solar);

  /// Sets the mean anomaly and mean motion at t_min [min] after epoch (dspace), given
  /// the elements after the lunar-solar secular drift. Integrates from epoch on every
  /// call with Vallado's fixed ±720 min Euler-Maclaurin steps: his code resumes from the
  /// last call instead, but its steps land on the same multiples of 720 min and do the
  /// same arithmetic, so the result is identical. Costs |t_min| / 720 steps.
  void apply(double t_min, Sgp4MeanElements& m) const;

 private:
  enum class Kind { kOneDay, kHalfDay };  // Vallado's irez 1 and 2

  /// Resonance coefficients (dsinit outputs) and epoch values the integration needs.
  struct Coefficients {
    double d2201 = 0.0, d2211 = 0.0, d3210 = 0.0, d3222 = 0.0, d4410 = 0.0;
    double d4422 = 0.0, d5220 = 0.0, d5232 = 0.0, d5421 = 0.0, d5433 = 0.0;
    double del1 = 0.0, del2 = 0.0, del3 = 0.0;
    double xlamo = 0.0;  // [rad] resonant longitude at epoch
    double xfact = 0.0;  // [rad/min] its rate less the mean motion
    double no = 0.0;     // [rad/min] mean motion at epoch
    double argpo = 0.0, argpdot = 0.0, gsto = 0.0;
  };

  /// Time derivatives of the resonant longitude and mean motion in the integrator.
  struct Dots {
    double xldot, xndt, xnddt;
  };

  Sgp4Resonance(Kind kind, const Coefficients& c) : kind_(kind), c_(c) {}
  Dots dots(double atime, double xli, double xni) const;

  Kind kind_;
  Coefficients c_;
};

}  // namespace flatsat::sim
