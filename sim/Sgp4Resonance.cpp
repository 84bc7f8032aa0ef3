// SPDX-License-Identifier: Apache-2.0
#include "sim/Sgp4Resonance.hpp"

#include <cmath>

#include "sim/Constants.hpp"

namespace flatsat::sim {
namespace {

/// [rad/min] Earth rotation rate used by SDP4 (7.29211514668855e-5 rad/s).
constexpr double kRptim = 4.37526908801129966e-3;
/// [min] integrator step, and step² / 2 for the second-order term.
constexpr double kStep = 720.0;
constexpr double kStep2 = 259200.0;
// Phases [rad] of the resonant tesseral terms (dspace constants).
constexpr double kFasx2 = 0.13130908, kFasx4 = 2.8843198, kFasx6 = 0.37448087;
constexpr double kG22 = 5.7686396, kG32 = 0.95240898, kG44 = 1.8014998, kG52 = 1.0508330, kG54 = 4.4108898;

}  // namespace

std::optional<Sgp4Resonance> Sgp4Resonance::of(const Epoch& epoch, const Sgp4LunarSolar::Rates& lunar_solar) {
  const Sgp4MeanElements& e = epoch.elements;
  const double nm = e.mean_motion;
  Kind kind;
  if (nm < 0.0052359877 && nm > 0.0034906585) {
    kind = Kind::kOneDay;  // periods of 20 to 30 h
  } else if (nm >= 8.26e-3 && nm <= 9.24e-3 && e.ecc >= 0.5) {
    kind = Kind::kHalfDay;  // periods of 11.3 to 12.7 h
  } else {
    return std::nullopt;
  }

  Coefficients c;
  c.no = nm;
  c.argpo = e.argp;
  c.argpdot = epoch.argpdot;
  c.gsto = epoch.gsto;
  const double cosim = std::cos(e.incl);
  const double sinim = std::sin(e.incl);
  const double em = e.ecc;
  const double emsq = em * em;
  const double theta = epoch.gsto;
  const double aonv = std::pow(nm / sgp4_wgs72::kXke, 2.0 / 3.0);

  if (kind == Kind::kHalfDay) {
    // Eccentricity functions G (polynomial fits in e) and inclination functions F of
    // the 2-2, 3-2, 4-4, 5-2, 5-4 tesseral terms.
    const double cosisq = cosim * cosim;
    const double eoc = em * emsq;
    const double g201 = -0.306 - (em - 0.64) * 0.440;
    double g211, g310, g322, g410, g422, g520, g521, g532, g533;
    if (em <= 0.65) {
      g211 = 3.616 - 13.2470 * em + 16.2900 * emsq;
      g310 = -19.302 + 117.3900 * em - 228.4190 * emsq + 156.5910 * eoc;
      g322 = -18.9068 + 109.7927 * em - 214.6334 * emsq + 146.5816 * eoc;
      g410 = -41.122 + 242.6940 * em - 471.0940 * emsq + 313.9530 * eoc;
      g422 = -146.407 + 841.8800 * em - 1629.014 * emsq + 1083.4350 * eoc;
      g520 = -532.114 + 3017.977 * em - 5740.032 * emsq + 3708.2760 * eoc;
    } else {
      g211 = -72.099 + 331.819 * em - 508.738 * emsq + 266.724 * eoc;
      g310 = -346.844 + 1582.851 * em - 2415.925 * emsq + 1246.113 * eoc;
      g322 = -342.585 + 1554.908 * em - 2366.899 * emsq + 1215.972 * eoc;
      g410 = -1052.797 + 4758.686 * em - 7193.992 * emsq + 3651.957 * eoc;
      g422 = -3581.690 + 16178.110 * em - 24462.770 * emsq + 12422.520 * eoc;
      g520 = em > 0.715 ? -5149.66 + 29936.92 * em - 54087.36 * emsq + 31324.56 * eoc
                        : 1464.74 - 4664.75 * em + 3763.64 * emsq;
    }
    if (em < 0.7) {
      g533 = -919.22770 + 4988.6100 * em - 9064.7700 * emsq + 5542.21 * eoc;
      g521 = -822.71072 + 4568.6173 * em - 8491.4146 * emsq + 5337.524 * eoc;
      g532 = -853.66600 + 4690.2500 * em - 8624.7700 * emsq + 5341.4 * eoc;
    } else {
      g533 = -37995.780 + 161616.52 * em - 229838.20 * emsq + 109377.94 * eoc;
      g521 = -51752.104 + 218913.95 * em - 309468.16 * emsq + 146349.42 * eoc;
      g532 = -40023.880 + 170470.89 * em - 242699.48 * emsq + 115605.82 * eoc;
    }
    const double sini2 = sinim * sinim;
    const double f220 = 0.75 * (1.0 + 2.0 * cosim + cosisq);
    const double f221 = 1.5 * sini2;
    const double f321 = 1.875 * sinim * (1.0 - 2.0 * cosim - 3.0 * cosisq);
    const double f322 = -1.875 * sinim * (1.0 + 2.0 * cosim - 3.0 * cosisq);
    const double f441 = 35.0 * sini2 * f220;
    const double f442 = 39.3750 * sini2 * sini2;
    const double f522 = 9.84375 * sinim *
                        (sini2 * (1.0 - 2.0 * cosim - 5.0 * cosisq) + 0.33333333 * (-2.0 + 4.0 * cosim + 6.0 * cosisq));
    const double f523 = sinim * (4.92187512 * sini2 * (-2.0 - 4.0 * cosim + 10.0 * cosisq) +
                                 6.56250012 * (1.0 + 2.0 * cosim - 3.0 * cosisq));
    const double f542 = 29.53125 * sinim * (2.0 - 8.0 * cosim + cosisq * (-12.0 + 8.0 * cosim + 10.0 * cosisq));
    const double f543 = 29.53125 * sinim * (-2.0 - 8.0 * cosim + cosisq * (12.0 + 8.0 * cosim - 10.0 * cosisq));
    // Normalised harmonic strengths (root22 … root54) scaled by n² and powers of 1/a.
    const double xno2 = nm * nm;
    const double ainv2 = aonv * aonv;
    double temp1 = 3.0 * xno2 * ainv2;
    double temp = temp1 * 1.7891679e-6;
    c.d2201 = temp * f220 * g201;
    c.d2211 = temp * f221 * g211;
    temp1 = temp1 * aonv;
    temp = temp1 * 3.7393792e-7;
    c.d3210 = temp * f321 * g310;
    c.d3222 = temp * f322 * g322;
    temp1 = temp1 * aonv;
    temp = 2.0 * temp1 * 7.3636953e-9;
    c.d4410 = temp * f441 * g410;
    c.d4422 = temp * f442 * g422;
    temp1 = temp1 * aonv;
    temp = temp1 * 1.1428639e-7;
    c.d5220 = temp * f522 * g520;
    c.d5232 = temp * f523 * g532;
    temp = 2.0 * temp1 * 2.1765803e-9;
    c.d5421 = temp * f542 * g521;
    c.d5433 = temp * f543 * g533;
    c.xlamo = std::fmod(e.mean_anomaly + e.node + e.node - theta - theta, kTwoPi);
    c.xfact = epoch.mdot + lunar_solar.dmdt + 2.0 * (epoch.nodedot + lunar_solar.dnodt - kRptim) - nm;
  } else {
    // Synchronous: the 2-2, 3-1 and 3-3 terms (q22, q31, q33).
    const double g200 = 1.0 + emsq * (-2.5 + 0.8125 * emsq);
    const double g310 = 1.0 + 2.0 * emsq;
    const double g300 = 1.0 + emsq * (-6.0 + 6.60937 * emsq);
    const double f220 = 0.75 * (1.0 + cosim) * (1.0 + cosim);
    const double f311 = 0.9375 * sinim * sinim * (1.0 + 3.0 * cosim) - 0.75 * (1.0 + cosim);
    double f330 = 1.0 + cosim;
    f330 = 1.875 * f330 * f330 * f330;
    c.del1 = 3.0 * nm * nm * aonv * aonv;
    c.del2 = 2.0 * c.del1 * f220 * g200 * 1.7891679e-6;
    c.del3 = 3.0 * c.del1 * f330 * g300 * 2.2123015e-7 * aonv;
    c.del1 = c.del1 * f311 * g310 * 2.1460748e-6 * aonv;
    c.xlamo = std::fmod(e.mean_anomaly + e.node + e.argp - theta, kTwoPi);
    const double xpidot = epoch.argpdot + epoch.nodedot;
    c.xfact = epoch.mdot + xpidot - kRptim + lunar_solar.dmdt + lunar_solar.domdt + lunar_solar.dnodt - nm;
  }
  return Sgp4Resonance(kind, c);
}

Sgp4Resonance::Dots Sgp4Resonance::dots(double atime, double xli, double xni) const {
  Dots d;
  d.xldot = xni + c_.xfact;
  if (kind_ == Kind::kOneDay) {
    d.xndt = c_.del1 * std::sin(xli - kFasx2) + c_.del2 * std::sin(2.0 * (xli - kFasx4)) +
             c_.del3 * std::sin(3.0 * (xli - kFasx6));
    d.xnddt = c_.del1 * std::cos(xli - kFasx2) + 2.0 * c_.del2 * std::cos(2.0 * (xli - kFasx4)) +
              3.0 * c_.del3 * std::cos(3.0 * (xli - kFasx6));
  } else {
    const double xomi = c_.argpo + c_.argpdot * atime;
    const double x2omi = xomi + xomi;
    const double x2li = xli + xli;
    d.xndt = c_.d2201 * std::sin(x2omi + xli - kG22) + c_.d2211 * std::sin(xli - kG22) +
             c_.d3210 * std::sin(xomi + xli - kG32) + c_.d3222 * std::sin(-xomi + xli - kG32) +
             c_.d4410 * std::sin(x2omi + x2li - kG44) + c_.d4422 * std::sin(x2li - kG44) +
             c_.d5220 * std::sin(xomi + xli - kG52) + c_.d5232 * std::sin(-xomi + xli - kG52) +
             c_.d5421 * std::sin(xomi + x2li - kG54) + c_.d5433 * std::sin(-xomi + x2li - kG54);
    d.xnddt = c_.d2201 * std::cos(x2omi + xli - kG22) + c_.d2211 * std::cos(xli - kG22) +
              c_.d3210 * std::cos(xomi + xli - kG32) + c_.d3222 * std::cos(-xomi + xli - kG32) +
              c_.d5220 * std::cos(xomi + xli - kG52) + c_.d5232 * std::cos(-xomi + xli - kG52) +
              2.0 * (c_.d4410 * std::cos(x2omi + x2li - kG44) + c_.d4422 * std::cos(x2li - kG44) +
                     c_.d5421 * std::cos(xomi + x2li - kG54) + c_.d5433 * std::cos(-xomi + x2li - kG54));
  }
  d.xnddt = d.xnddt * d.xldot;
  return d;
}

void Sgp4Resonance::apply(double t_min, Sgp4MeanElements& m) const {
  const double theta = std::fmod(c_.gsto + t_min * kRptim, kTwoPi);
  const double delt = t_min > 0.0 ? kStep : -kStep;
  double atime = 0.0;
  double xli = c_.xlamo;
  double xni = c_.no;
  Dots d = dots(atime, xli, xni);
  while (std::fabs(t_min - atime) >= kStep) {
    xli = xli + d.xldot * delt + d.xndt * kStep2;
    xni = xni + d.xndt * delt + d.xnddt * kStep2;
    atime = atime + delt;
    d = dots(atime, xli, xni);
  }
  const double ft = t_min - atime;
  const double nm = xni + d.xndt * ft + d.xnddt * ft * ft * 0.5;
  const double xl = xli + d.xldot * ft + d.xndt * ft * ft * 0.5;
  m.mean_anomaly = kind_ == Kind::kHalfDay ? xl - 2.0 * m.node + 2.0 * theta : xl - m.node - m.argp + theta;
  // n = n0 + (n − n0) as in Vallado's code, which rounds differently from n itself.
  const double dndt = nm - c_.no;
  m.mean_motion = c_.no + dndt;
}

}  // namespace flatsat::sim
