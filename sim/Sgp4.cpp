// SPDX-License-Identifier: Apache-2.0
// SGP4 initialisation: Vallado et al. 2006 (AIAA 2006-6753), procedures twoline2rv
// (units), initl and sgp4init of its reference code. Propagation is in
// Sgp4Propagate.cpp. Variable names follow that code so each line can be checked
// against it; the order of the floating-point operations is kept too, because the
// verification compares velocities to 1e-9 km/s.
#include "sim/Sgp4.hpp"

#include <cmath>
#include <stdexcept>

#include "sim/Constants.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {
namespace {

/// [d] Julian date of 1950 January 0.0 UTC, the origin of SGP4's epoch.
constexpr double kJulianDate1950Jan0 = 2433281.5;

}  // namespace

Sgp4::Sgp4(const Tle& tle) {
  using namespace sgp4_wgs72;
  const std::vector<std::string> errors = tle.validate();
  if (!errors.empty()) {
    std::string message = "Sgp4: invalid TLE: " + errors.front();
    for (std::size_t i = 1; i < errors.size(); ++i) message += "; " + errors[i];
    throw std::invalid_argument(message);
  }

  // twoline2rv: TLE units to radians and radians per minute.
  const double xpdotp = 1440.0 / (2.0 * kPi);  // [rev/d per rad/min]
  const double deg2rad = kPi / 180.0;
  const double no_kozai = tle.mean_motion_rev_day / xpdotp;
  c_.bstar = tle.bstar;
  epoch_.ecc = tle.eccentricity;
  epoch_.incl = tle.inclination_deg * deg2rad;
  epoch_.node = tle.raan_deg * deg2rad;
  epoch_.argp = tle.arg_perigee_deg * deg2rad;
  epoch_.mean_anomaly = tle.mean_anomaly_deg * deg2rad;

  // Epoch as Vallado forms it: day of year to hours, minutes and seconds (days2mdhms),
  // then whole Julian days plus the day fraction (jday, Vallado 2013 Alg. 14); the
  // round trip decides the last bit of the epoch, which the deep-space terms see.
  const int day_of_year = static_cast<int>(std::floor(tle.epoch_day));
  epoch_jd_ = julianDate(UtcEpoch{tle.epoch_year, 1, 1, 0, 0, 0.0}) + (day_of_year - 1);
  const double hours = (tle.epoch_day - day_of_year) * 24.0;
  const double hr = std::floor(hours);
  const double minutes = (hours - hr) * 60.0;
  const double minute = std::floor(minutes);
  const double sec = (minutes - minute) * 60.0;
  epoch_jd_fraction_ = (sec + minute * 60.0 + hr * 3600.0) / 86400.0;
  const double epoch = (epoch_jd_ + epoch_jd_fraction_) - kJulianDate1950Jan0;  // [d] since 1950 Jan 0

  // initl: recover Brouwer's mean motion from the TLE's Kozai mean motion (STR #3).
  const double x2o3 = 2.0 / 3.0;
  const double ecco = epoch_.ecc;
  const double eccsq = ecco * ecco;
  const double omeosq = 1.0 - eccsq;
  const double rteosq = std::sqrt(omeosq);
  const double cosio = std::cos(epoch_.incl);
  const double cosio2 = cosio * cosio;
  const double ak = std::pow(kXke / no_kozai, x2o3);
  const double d1 = 0.75 * kJ2 * (3.0 * cosio2 - 1.0) / (rteosq * omeosq);
  double del = d1 / (ak * ak);
  const double adel = ak * (1.0 - del * del - del * (1.0 / 3.0 + 134.0 * del * del / 81.0));
  del = d1 / (adel * adel);
  const double no = no_kozai / (1.0 + del);
  epoch_.mean_motion = no;
  const double ao = std::pow(kXke / no, x2o3);
  const double sinio = std::sin(epoch_.incl);
  const double po = ao * omeosq;
  const double con42 = 1.0 - 5.0 * cosio2;
  c_.con41 = -con42 - cosio2 - cosio2;
  const double posq = po * po;
  const double rp = ao * (1.0 - ecco);
  // GMST at epoch, IAU-82 (Vallado's gstime and gmst_rad: Vallado Eq. 3-47); used by the
  // resonance terms only.
  const double gsto = gmst_rad(epoch + kJulianDate1950Jan0);

  // sgp4init: drag and gravity coefficients. The atmosphere's density parameter s and
  // (q0 - s)^4 are lowered for perigees below 156 km (98 km floor), as in STR #3.
  const double ss = 78.0 / kRadius_km + 1.0;
  const double qzms2ttemp = (120.0 - 78.0) / kRadius_km;
  const double qzms2t = qzms2ttemp * qzms2ttemp * qzms2ttemp * qzms2ttemp;
  simple_drag_ = rp < (220.0 / kRadius_km + 1.0);
  double sfour = ss;
  double qzms24 = qzms2t;
  const double perige = (rp - 1.0) * kRadius_km;
  if (perige < 156.0) {
    sfour = perige < 98.0 ? 20.0 : perige - 78.0;
    const double qzms24temp = (120.0 - sfour) / kRadius_km;
    qzms24 = qzms24temp * qzms24temp * qzms24temp * qzms24temp;
    sfour = sfour / kRadius_km + 1.0;
  }
  const double pinvsq = 1.0 / posq;
  const double tsi = 1.0 / (ao - sfour);
  c_.eta = ao * ecco * tsi;
  const double etasq = c_.eta * c_.eta;
  const double eeta = ecco * c_.eta;
  const double psisq = std::fabs(1.0 - etasq);
  const double coef = qzms24 * std::pow(tsi, 4.0);
  const double coef1 = coef / std::pow(psisq, 3.5);
  const double cc2 = coef1 * no *
                     (ao * (1.0 + 1.5 * etasq + eeta * (4.0 + etasq)) +
                      0.375 * kJ2 * tsi / psisq * c_.con41 * (8.0 + 3.0 * etasq * (8.0 + etasq)));
  c_.cc1 = c_.bstar * cc2;
  // The J3 drag terms divide by e: dropped for near-circular orbits.
  const double cc3 = ecco > 1.0e-4 ? -2.0 * coef * tsi * kJ3OverJ2 * no * sinio / ecco : 0.0;
  c_.x1mth2 = 1.0 - cosio2;
  c_.cc4 = 2.0 * no * coef1 * ao * omeosq *
           (c_.eta * (2.0 + 0.5 * etasq) + ecco * (0.5 + 2.0 * etasq) -
            kJ2 * tsi / (ao * psisq) *
                (-3.0 * c_.con41 * (1.0 - 2.0 * eeta + etasq * (1.5 - 0.5 * eeta)) +
                 0.75 * c_.x1mth2 * (2.0 * etasq - eeta * (1.0 + etasq)) * std::cos(2.0 * epoch_.argp)));
  c_.cc5 = 2.0 * coef1 * ao * omeosq * (1.0 + 2.75 * (etasq + eeta) + eeta * etasq);
  const double cosio4 = cosio2 * cosio2;
  const double temp1 = 1.5 * kJ2 * pinvsq * no;
  const double temp2 = 0.5 * temp1 * kJ2 * pinvsq;
  const double temp3 = -0.46875 * kJ4 * pinvsq * pinvsq * no;
  c_.mdot = no + 0.5 * temp1 * rteosq * c_.con41 + 0.0625 * temp2 * rteosq * (13.0 - 78.0 * cosio2 + 137.0 * cosio4);
  c_.argpdot = -0.5 * temp1 * con42 + 0.0625 * temp2 * (7.0 - 114.0 * cosio2 + 395.0 * cosio4) +
               temp3 * (3.0 - 36.0 * cosio2 + 49.0 * cosio4);
  const double xhdot1 = -temp1 * cosio;
  c_.nodedot = xhdot1 + (0.5 * temp2 * (4.0 - 19.0 * cosio2) + 2.0 * temp3 * (3.0 - 7.0 * cosio2)) * cosio;
  c_.omgcof = c_.bstar * cc3 * std::cos(epoch_.argp);
  c_.xmcof = ecco > 1.0e-4 ? -x2o3 * coef * c_.bstar / eeta : 0.0;
  c_.nodecf = 3.5 * omeosq * xhdot1 * c_.cc1;
  c_.t2cof = 1.5 * c_.cc1;
  // 1 + cos i vanishes at 180 deg: Vallado divides by 1.5e-12 there instead.
  const double one_plus_cosio = std::fabs(cosio + 1.0) > 1.5e-12 ? 1.0 + cosio : 1.5e-12;
  c_.xlcof = -0.25 * kJ3OverJ2 * sinio * (3.0 + 5.0 * cosio) / one_plus_cosio;
  c_.aycof = -0.5 * kJ3OverJ2 * sinio;
  const double delmotemp = 1.0 + c_.eta * std::cos(epoch_.mean_anomaly);
  c_.delmo = delmotemp * delmotemp * delmotemp;
  c_.sinmao = std::sin(epoch_.mean_anomaly);
  c_.x7thm1 = 7.0 * cosio2 - 1.0;

  if (2.0 * kPi / no >= 225.0) {
    // Deep space (SDP4): third-body terms, resonance, and only the simple drag terms.
    simple_drag_ = true;
    lunar_solar_.emplace(epoch, epoch_);
    resonance_ = Sgp4Resonance::of({epoch_, c_.mdot, c_.argpdot, c_.nodedot, gsto}, lunar_solar_->rates());
  } else if (!simple_drag_) {
    // Higher-order drag terms, for perigees above 220 km.
    const double cc1sq = c_.cc1 * c_.cc1;
    c_.d2 = 4.0 * ao * tsi * cc1sq;
    const double temp = c_.d2 * tsi * c_.cc1 / 3.0;
    c_.d3 = (17.0 * ao + sfour) * temp;
    c_.d4 = 0.5 * temp * ao * tsi * (221.0 * ao + 31.0 * sfour) * c_.cc1;
    c_.t3cof = c_.d2 + 2.0 * cc1sq;
    c_.t4cof = 0.25 * (3.0 * c_.d3 + c_.cc1 * (12.0 * c_.d2 + 10.0 * cc1sq));
    c_.t5cof = 0.2 * (3.0 * c_.d4 + 12.0 * c_.cc1 * c_.d3 + 6.0 * c_.d2 * c_.d2 + 15.0 * cc1sq * (2.0 * c_.d2 + cc1sq));
  }
}

}  // namespace flatsat::sim
