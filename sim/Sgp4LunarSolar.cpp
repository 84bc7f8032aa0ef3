// SPDX-License-Identifier: Apache-2.0
#include "sim/Sgp4LunarSolar.hpp"

#include <cmath>

#include "sim/Constants.hpp"

namespace flatsat::sim {
namespace {

// Mean motions [rad/min] and eccentricities of the Sun's and the Moon's apparent
// orbits (dpper and dsinit constants).
constexpr double kZns = 1.19459e-5;
constexpr double kZes = 0.01675;
constexpr double kZnl = 1.5835218e-4;
constexpr double kZel = 0.05490;
// Below 3 deg (and above 177 deg) the node rates are dropped: divided by sin i they
// would blow up (Vallado's "sgp4fix for 180 deg incl").
constexpr double kNearEquatorial_rad = 5.2359877e-2;

/// Orientation of a perturbing body's orbit (cos/sin of its perigee argument g,
/// inclination i and node h referred to the satellite's node) and its strength cc.
struct Body {
  double zcosg, zsing, zcosi, zsini, zcosh, zsinh, cc;
};

/// dscom's per-body terms: s1..s7 and the z coefficients.
struct Terms {
  double s1, s2, s3, s4, s5, s6, s7;
  double z1, z2, z3, z11, z12, z13, z21, z22, z23, z31, z32, z33;
};

Terms bodyTerms(const Body& b, double cosim, double sinim, double cosomm, double sinomm, double em, double emsq,
                double rtemsq, double xnoi) {
  const double betasq = 1.0 - emsq;
  const double a1 = b.zcosg * b.zcosh + b.zsing * b.zcosi * b.zsinh;
  const double a3 = -b.zsing * b.zcosh + b.zcosg * b.zcosi * b.zsinh;
  const double a7 = -b.zcosg * b.zsinh + b.zsing * b.zcosi * b.zcosh;
  const double a8 = b.zsing * b.zsini;
  const double a9 = b.zsing * b.zsinh + b.zcosg * b.zcosi * b.zcosh;
  const double a10 = b.zcosg * b.zsini;
  const double a2 = cosim * a7 + sinim * a8;
  const double a4 = cosim * a9 + sinim * a10;
  const double a5 = -sinim * a7 + cosim * a8;
  const double a6 = -sinim * a9 + cosim * a10;

  const double x1 = a1 * cosomm + a2 * sinomm;
  const double x2 = a3 * cosomm + a4 * sinomm;
  const double x3 = -a1 * sinomm + a2 * cosomm;
  const double x4 = -a3 * sinomm + a4 * cosomm;
  const double x5 = a5 * sinomm;
  const double x6 = a6 * sinomm;
  const double x7 = a5 * cosomm;
  const double x8 = a6 * cosomm;

  Terms t;
  t.z31 = 12.0 * x1 * x1 - 3.0 * x3 * x3;
  t.z32 = 24.0 * x1 * x2 - 6.0 * x3 * x4;
  t.z33 = 12.0 * x2 * x2 - 3.0 * x4 * x4;
  t.z1 = 3.0 * (a1 * a1 + a2 * a2) + t.z31 * emsq;
  t.z2 = 6.0 * (a1 * a3 + a2 * a4) + t.z32 * emsq;
  t.z3 = 3.0 * (a3 * a3 + a4 * a4) + t.z33 * emsq;
  t.z11 = -6.0 * a1 * a5 + emsq * (-24.0 * x1 * x7 - 6.0 * x3 * x5);
  t.z12 = -6.0 * (a1 * a6 + a3 * a5) + emsq * (-24.0 * (x2 * x7 + x1 * x8) - 6.0 * (x3 * x6 + x4 * x5));
  t.z13 = -6.0 * a3 * a6 + emsq * (-24.0 * x2 * x8 - 6.0 * x4 * x6);
  t.z21 = 6.0 * a2 * a5 + emsq * (24.0 * x1 * x5 - 6.0 * x3 * x7);
  t.z22 = 6.0 * (a4 * a5 + a2 * a6) + emsq * (24.0 * (x2 * x5 + x1 * x6) - 6.0 * (x4 * x7 + x3 * x8));
  t.z23 = 6.0 * a4 * a6 + emsq * (24.0 * x2 * x6 - 6.0 * x4 * x8);
  t.z1 = t.z1 + t.z1 + betasq * t.z31;
  t.z2 = t.z2 + t.z2 + betasq * t.z32;
  t.z3 = t.z3 + t.z3 + betasq * t.z33;
  t.s3 = b.cc * xnoi;
  t.s2 = -0.5 * t.s3 / rtemsq;
  t.s4 = t.s3 * rtemsq;
  t.s1 = -15.0 * em * t.s4;
  t.s5 = x1 * x3 + x2 * x4;
  t.s6 = x2 * x3 + x1 * x4;
  t.s7 = x2 * x4 - x1 * x3;
  return t;
}

}  // namespace

Sgp4LunarSolar::Sgp4LunarSolar(double epoch_days_1950, const Sgp4MeanElements& epoch) {
  // dscom: geometry of the Sun's and the Moon's orbits at epoch.
  const double em = epoch.ecc;
  const double snodm = std::sin(epoch.node);
  const double cnodm = std::cos(epoch.node);
  const double sinomm = std::sin(epoch.argp);
  const double cosomm = std::cos(epoch.argp);
  const double sinim = std::sin(epoch.incl);
  const double cosim = std::cos(epoch.incl);
  const double emsq = em * em;
  const double rtemsq = std::sqrt(1.0 - emsq);

  // Days since 1900 January 0.5 (the epoch of the lunar theory's constants).
  const double day = epoch_days_1950 + 18261.5;
  const double xnodce = std::fmod(4.5236020 - 9.2422029e-4 * day, kTwoPi);
  const double stem = std::sin(xnodce);
  const double ctem = std::cos(xnodce);
  const double zcosil = 0.91375164 - 0.03568096 * ctem;
  const double zsinil = std::sqrt(1.0 - zcosil * zcosil);
  const double zsinhl = 0.089683511 * stem / zsinil;
  const double zcoshl = std::sqrt(1.0 - zsinhl * zsinhl);
  const double gam = 5.8351514 + 0.0019443680 * day;
  double zx = 0.39785416 * stem / zsinil;
  const double zy = zcoshl * ctem + 0.91744867 * zsinhl * stem;
  zx = std::atan2(zx, zy);
  zx = gam + zx - xnodce;

  const double xnoi = 1.0 / epoch.mean_motion;
  // The Sun: fixed ecliptic orbit (obliquity, perigee) with strength c1ss.
  const Body sun{0.1945905, -0.98088458, 0.91744867, 0.39785416, cnodm, snodm, 2.9864797e-6};
  // The Moon: its orbit's inclination, node and perigee at epoch, with strength c1l.
  const Body moon{
      std::cos(zx), std::sin(zx), zcosil, zsinil, zcoshl * cnodm + zsinhl * snodm, snodm * zcoshl - cnodm * zsinhl,
      4.7968065e-7};
  const Terms s = bodyTerms(sun, cosim, sinim, cosomm, sinomm, em, emsq, rtemsq, xnoi);
  const Terms l = bodyTerms(moon, cosim, sinim, cosomm, sinomm, em, emsq, rtemsq, xnoi);

  p_.zmol = std::fmod(4.7199672 + 0.22997150 * day - gam, kTwoPi);
  p_.zmos = std::fmod(6.2565837 + 0.017201977 * day, kTwoPi);

  p_.se2 = 2.0 * s.s1 * s.s6;
  p_.se3 = 2.0 * s.s1 * s.s7;
  p_.si2 = 2.0 * s.s2 * s.z12;
  p_.si3 = 2.0 * s.s2 * (s.z13 - s.z11);
  p_.sl2 = -2.0 * s.s3 * s.z2;
  p_.sl3 = -2.0 * s.s3 * (s.z3 - s.z1);
  p_.sl4 = -2.0 * s.s3 * (-21.0 - 9.0 * emsq) * kZes;
  p_.sgh2 = 2.0 * s.s4 * s.z32;
  p_.sgh3 = 2.0 * s.s4 * (s.z33 - s.z31);
  p_.sgh4 = -18.0 * s.s4 * kZes;
  p_.sh2 = -2.0 * s.s2 * s.z22;
  p_.sh3 = -2.0 * s.s2 * (s.z23 - s.z21);

  p_.ee2 = 2.0 * l.s1 * l.s6;
  p_.e3 = 2.0 * l.s1 * l.s7;
  p_.xi2 = 2.0 * l.s2 * l.z12;
  p_.xi3 = 2.0 * l.s2 * (l.z13 - l.z11);
  p_.xl2 = -2.0 * l.s3 * l.z2;
  p_.xl3 = -2.0 * l.s3 * (l.z3 - l.z1);
  p_.xl4 = -2.0 * l.s3 * (-21.0 - 9.0 * emsq) * kZel;
  p_.xgh2 = 2.0 * l.s4 * l.z32;
  p_.xgh3 = 2.0 * l.s4 * (l.z33 - l.z31);
  p_.xgh4 = -18.0 * l.s4 * kZel;
  p_.xh2 = -2.0 * l.s2 * l.z22;
  p_.xh3 = -2.0 * l.s2 * (l.z23 - l.z21);

  // dsinit: secular rates, solar then lunar.
  const bool near_equatorial = epoch.incl < kNearEquatorial_rad || epoch.incl > kPi - kNearEquatorial_rad;
  const double ses = s.s1 * kZns * s.s5;
  const double sis = s.s2 * kZns * (s.z11 + s.z13);
  const double sls = -kZns * s.s3 * (s.z1 + s.z3 - 14.0 - 6.0 * emsq);
  const double sghs = s.s4 * kZns * (s.z31 + s.z33 - 6.0);
  double shs = near_equatorial ? 0.0 : -kZns * s.s2 * (s.z21 + s.z23);
  if (sinim != 0.0) shs = shs / sinim;
  const double sgs = sghs - cosim * shs;

  rates_.dedt = ses + l.s1 * kZnl * l.s5;
  rates_.didt = sis + l.s2 * kZnl * (l.z11 + l.z13);
  rates_.dmdt = sls - kZnl * l.s3 * (l.z1 + l.z3 - 14.0 - 6.0 * emsq);
  const double sghl = l.s4 * kZnl * (l.z31 + l.z33 - 6.0);
  const double shll = near_equatorial ? 0.0 : -kZnl * l.s2 * (l.z21 + l.z23);
  rates_.domdt = sgs + sghl;
  rates_.dnodt = shs;
  if (sinim != 0.0) {
    rates_.domdt = rates_.domdt - cosim / sinim * shll;
    rates_.dnodt = rates_.dnodt + shll / sinim;
  }
}

void Sgp4LunarSolar::applySecular(double t_min, Sgp4MeanElements& m) const {
  m.ecc = m.ecc + rates_.dedt * t_min;
  m.incl = m.incl + rates_.didt * t_min;
  m.argp = m.argp + rates_.domdt * t_min;
  m.node = m.node + rates_.dnodt * t_min;
  m.mean_anomaly = m.mean_anomaly + rates_.dmdt * t_min;
}

void Sgp4LunarSolar::applyPeriodics(double t_min, Sgp4MeanElements& m) const {
  // Solar terms at the Sun's mean anomaly zm (true anomaly approximated to first order in e).
  double zm = p_.zmos + kZns * t_min;
  double zf = zm + 2.0 * kZes * std::sin(zm);
  double sinzf = std::sin(zf);
  double f2 = 0.5 * sinzf * sinzf - 0.25;
  double f3 = -0.5 * sinzf * std::cos(zf);
  const double ses = p_.se2 * f2 + p_.se3 * f3;
  const double sis = p_.si2 * f2 + p_.si3 * f3;
  const double sls = p_.sl2 * f2 + p_.sl3 * f3 + p_.sl4 * sinzf;
  const double sghs = p_.sgh2 * f2 + p_.sgh3 * f3 + p_.sgh4 * sinzf;
  const double shs = p_.sh2 * f2 + p_.sh3 * f3;
  // Lunar terms.
  zm = p_.zmol + kZnl * t_min;
  zf = zm + 2.0 * kZel * std::sin(zm);
  sinzf = std::sin(zf);
  f2 = 0.5 * sinzf * sinzf - 0.25;
  f3 = -0.5 * sinzf * std::cos(zf);
  const double sel = p_.ee2 * f2 + p_.e3 * f3;
  const double sil = p_.xi2 * f2 + p_.xi3 * f3;
  const double sll = p_.xl2 * f2 + p_.xl3 * f3 + p_.xl4 * sinzf;
  const double sghl = p_.xgh2 * f2 + p_.xgh3 * f3 + p_.xgh4 * sinzf;
  const double shll = p_.xh2 * f2 + p_.xh3 * f3;
  // Vallado's code subtracts the epoch values of these sums (peo, pinco, …), which it
  // sets to zero, so the periodics are applied as they are.
  const double pe = ses + sel;
  const double pinc = sis + sil;
  const double pl = sls + sll;
  double pgh = sghs + sghl;
  double ph = shs + shll;

  m.incl = m.incl + pinc;
  m.ecc = m.ecc + pe;
  const double sinip = std::sin(m.incl);
  const double cosip = std::cos(m.incl);
  // The switch to Lyddane's form tests the perturbed inclination (GSFC's choice, kept
  // by Vallado; STR #3 tested the epoch inclination).
  if (m.incl >= 0.2) {
    ph = ph / sinip;
    pgh = pgh - cosip * ph;
    m.argp = m.argp + pgh;
    m.node = m.node + ph;
    m.mean_anomaly = m.mean_anomaly + pl;
    return;
  }
  // Lyddane's modification: at low inclination apply the node and perigee periodics
  // through the non-singular (sin i sin Ω, sin i cos Ω) and the longitude, then
  // recover Ω by atan2 on the branch closest to the unperturbed node.
  const double sinop = std::sin(m.node);
  const double cosop = std::cos(m.node);
  double alfdp = sinip * sinop;
  double betdp = sinip * cosop;
  const double dalf = ph * cosop + pinc * cosip * sinop;
  const double dbet = -ph * sinop + pinc * cosip * cosop;
  alfdp = alfdp + dalf;
  betdp = betdp + dbet;
  m.node = std::fmod(m.node, kTwoPi);
  double xls = m.mean_anomaly + m.argp + cosip * m.node;
  const double dls = pl + pgh - pinc * m.node * sinip;
  xls = xls + dls;
  const double xnoh = m.node;
  m.node = std::atan2(alfdp, betdp);
  if (std::fabs(xnoh - m.node) > kPi) m.node = m.node < xnoh ? m.node + kTwoPi : m.node - kTwoPi;
  m.mean_anomaly = m.mean_anomaly + pl;
  m.argp = xls - m.mean_anomaly - cosip * m.node;
}

}  // namespace flatsat::sim
