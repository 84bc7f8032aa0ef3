// SPDX-License-Identifier: Apache-2.0
// SGP4 propagation: Vallado et al. 2006 (AIAA 2006-6753), procedure sgp4 of its
// reference code (secular gravity and drag, deep-space terms, long-period periodics,
// Kepler's equation, short-period periodics). Variable names and the order of the
// floating-point operations follow that code (see Sgp4.cpp).
#include <cmath>
#include <limits>

#include "sim/Constants.hpp"
#include "sim/Format.hpp"
#include "sim/Sgp4.hpp"

namespace flatsat::sim {
namespace {

Sgp4::Result failure(Sgp4::Error error, const std::string& message) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return Sgp4::Result{error, message, Eigen::Vector3d::Constant(nan), Eigen::Vector3d::Constant(nan)};
}

/// -0.25 J3/J2 sin i (3 + 5 cos i) / (1 + cos i), guarded at i = 180 deg like Vallado.
double xlcofOf(double sinip, double cosip) {
  const double one_plus_cosip = std::fabs(cosip + 1.0) > 1.5e-12 ? 1.0 + cosip : 1.5e-12;
  return -0.25 * sgp4_wgs72::kJ3OverJ2 * sinip * (3.0 + 5.0 * cosip) / one_plus_cosip;
}

}  // namespace

Sgp4::Result Sgp4::propagate(double t) const {
  using namespace sgp4_wgs72;
  const double x2o3 = 2.0 / 3.0;

  // Secular gravity (J2, J4) and atmospheric drag.
  const double xmdf = epoch_.mean_anomaly + c_.mdot * t;
  const double argpdf = epoch_.argp + c_.argpdot * t;
  const double nodedf = epoch_.node + c_.nodedot * t;
  Sgp4MeanElements m;
  m.argp = argpdf;
  m.mean_anomaly = xmdf;
  const double t2 = t * t;
  m.node = nodedf + c_.nodecf * t2;
  double tempa = 1.0 - c_.cc1 * t;
  double tempe = c_.bstar * c_.cc4 * t;
  double templ = c_.t2cof * t2;
  if (!simple_drag_) {
    const double delomg = c_.omgcof * t;
    const double delmtemp = 1.0 + c_.eta * std::cos(xmdf);
    const double delm = c_.xmcof * (delmtemp * delmtemp * delmtemp - c_.delmo);
    const double temp = delomg + delm;
    m.mean_anomaly = xmdf + temp;
    m.argp = argpdf - temp;
    const double t3 = t2 * t;
    const double t4 = t3 * t;
    tempa = tempa - c_.d2 * t2 - c_.d3 * t3 - c_.d4 * t4;
    tempe = tempe + c_.bstar * c_.cc5 * (std::sin(m.mean_anomaly) - c_.sinmao);
    templ = templ + c_.t3cof * t3 + t4 * (c_.t4cof + t * c_.t5cof);
  }
  m.mean_motion = epoch_.mean_motion;
  m.ecc = epoch_.ecc;
  m.incl = epoch_.incl;
  if (lunar_solar_) {
    lunar_solar_->applySecular(t, m);
    if (resonance_) resonance_->apply(t, m);
  }

  if (m.mean_motion <= 0.0) {
    return failure(Error::kMeanMotion,
                   "mean motion " + formatNumber(m.mean_motion) + " rad/min is not positive (SGP4 error 2)");
  }
  const double am = std::pow(kXke / m.mean_motion, x2o3) * tempa * tempa;
  const double nm = kXke / std::pow(am, 1.5);
  double em = m.ecc - tempe;
  if (em >= 1.0 || em < -0.001) {
    return failure(Error::kMeanEccentricity,
                   "mean eccentricity " + formatNumber(em) + " outside [-0.001, 1) (SGP4 error 1)");
  }
  // Floor e to keep the divisions by e below finite.
  if (em < 1.0e-6) em = 1.0e-6;
  double mm = m.mean_anomaly + epoch_.mean_motion * templ;
  double xlm = mm + m.argp + m.node;
  const double nodem = std::fmod(m.node, kTwoPi);
  const double argpm = std::fmod(m.argp, kTwoPi);
  xlm = std::fmod(xlm, kTwoPi);
  mm = std::fmod(xlm - argpm - nodem, kTwoPi);

  // Lunar-solar long-period periodics; the short-period terms below then use the
  // perturbed inclination.
  Sgp4MeanElements p{em, m.incl, nodem, argpm, mm, nm};
  double sinip = std::sin(m.incl);
  double cosip = std::cos(m.incl);
  double aycof = c_.aycof;
  double xlcof = c_.xlcof;
  double con41 = c_.con41;
  double x1mth2 = c_.x1mth2;
  double x7thm1 = c_.x7thm1;
  if (lunar_solar_) {
    lunar_solar_->applyPeriodics(t, p);
    if (p.incl < 0.0) {
      p.incl = -p.incl;
      p.node = p.node + kPi;
      p.argp = p.argp - kPi;
    }
    if (p.ecc < 0.0 || p.ecc > 1.0) {
      return failure(Error::kPerturbedEccentricity,
                     "perturbed eccentricity " + formatNumber(p.ecc) + " outside [0, 1] (SGP4 error 3)");
    }
    sinip = std::sin(p.incl);
    cosip = std::cos(p.incl);
    aycof = -0.5 * kJ3OverJ2 * sinip;
    xlcof = xlcofOf(sinip, cosip);
    const double cosisq = cosip * cosip;
    con41 = 3.0 * cosisq - 1.0;
    x1mth2 = 1.0 - cosisq;
    x7thm1 = 7.0 * cosisq - 1.0;
  }

  // Long-period periodics of J3, in the non-singular (e cos ω, e sin ω) variables.
  const double axnl = p.ecc * std::cos(p.argp);
  double temp = 1.0 / (am * (1.0 - p.ecc * p.ecc));
  const double aynl = p.ecc * std::sin(p.argp) + temp * aycof;
  const double xl = p.mean_anomaly + p.argp + p.node + temp * xlcof * axnl;

  // Kepler's equation for the eccentric longitude E + ω: Newton steps limited to
  // ±0.95 rad and at most 10 iterations (Vallado's fix for high eccentricities).
  const double u = std::fmod(xl - p.node, kTwoPi);
  double eo1 = u;
  double tem5 = 9999.9;
  double sineo1 = 0.0;
  double coseo1 = 0.0;
  for (int ktr = 1; std::fabs(tem5) >= 1.0e-12 && ktr <= 10; ++ktr) {
    sineo1 = std::sin(eo1);
    coseo1 = std::cos(eo1);
    tem5 = 1.0 - coseo1 * axnl - sineo1 * aynl;
    tem5 = (u - aynl * coseo1 + axnl * sineo1 - eo1) / tem5;
    if (std::fabs(tem5) >= 0.95) tem5 = tem5 > 0.0 ? 0.95 : -0.95;
    eo1 = eo1 + tem5;
  }

  // Short-period preliminary quantities.
  const double ecose = axnl * coseo1 + aynl * sineo1;
  const double esine = axnl * sineo1 - aynl * coseo1;
  const double el2 = axnl * axnl + aynl * aynl;
  const double pl = am * (1.0 - el2);
  if (pl < 0.0) {
    return failure(Error::kSemiLatusRectum,
                   "semi-latus rectum " + formatNumber(pl) + " Earth radii is negative (SGP4 error 4)");
  }
  const double rl = am * (1.0 - ecose);
  const double rdotl = std::sqrt(am) * esine / rl;
  const double rvdotl = std::sqrt(pl) / rl;
  const double betal = std::sqrt(1.0 - el2);
  temp = esine / (1.0 + betal);
  const double sinu = am / rl * (sineo1 - aynl - axnl * temp);
  const double cosu = am / rl * (coseo1 - axnl + aynl * temp);
  double su = std::atan2(sinu, cosu);
  const double sin2u = (cosu + cosu) * sinu;
  const double cos2u = 1.0 - 2.0 * sinu * sinu;
  temp = 1.0 / pl;
  const double temp1 = 0.5 * kJ2 * temp;
  const double temp2 = temp1 * temp;

  // Short-period periodics of J2.
  const double mrt = rl * (1.0 - 1.5 * temp2 * betal * con41) + 0.5 * temp1 * x1mth2 * cos2u;
  if (mrt < 1.0) {
    return failure(Error::kDecayed,
                   "radius " + formatNumber(mrt) + " Earth radii is below the surface: decayed (SGP4 error 6)");
  }
  su = su - 0.25 * temp2 * x7thm1 * sin2u;
  const double xnode = p.node + 1.5 * temp2 * cosip * sin2u;
  const double xinc = p.incl + 1.5 * temp2 * cosip * sinip * cos2u;
  const double mvt = rdotl - nm * temp1 * x1mth2 * sin2u / kXke;
  const double rvdot = rvdotl + nm * temp1 * (x1mth2 * cos2u + 1.5 * con41) / kXke;

  // Orientation: unit vectors along the radius (u) and the in-plane normal to it (v).
  const double sinsu = std::sin(su);
  const double cossu = std::cos(su);
  const double snod = std::sin(xnode);
  const double cnod = std::cos(xnode);
  const double sini = std::sin(xinc);
  const double cosi = std::cos(xinc);
  const double xmx = -snod * cosi;
  const double xmy = cnod * cosi;
  const Eigen::Vector3d u_T(xmx * sinsu + cnod * cossu, xmy * sinsu + snod * cossu, sini * sinsu);
  const Eigen::Vector3d v_T(xmx * cossu - cnod * sinsu, xmy * cossu - snod * sinsu, sini * cossu);

  const double vkmpersec = kRadius_km * kXke / 60.0;  // [km/s per Earth radius/min]
  Result result;
  for (int k = 0; k < 3; ++k) {
    result.r_T_km[k] = (mrt * u_T[k]) * kRadius_km;
    result.v_T_km_s[k] = (mvt * u_T[k] + rvdot * v_T[k]) * vkmpersec;
  }
  return result;
}

}  // namespace flatsat::sim
