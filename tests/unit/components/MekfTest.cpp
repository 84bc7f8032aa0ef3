// SPDX-License-Identifier: Apache-2.0
// The MEKF on a simulated Sun-pointing, rolling spacecraft in a 560 km, 53° orbit: truth from
// sim/ (Kepler orbit, Sun ephemeris and shadow, tilted-dipole field), measurements from the
// rig's own sensor models with datasheet-typical noise.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "components/estimator/Mekf.hpp"
#include "components/common/onboard/ReferenceModel.hpp"
#include "components/gyro/GyroModel.hpp"
#include "components/magnetometer/MagnetometerModel.hpp"
#include "components/sun_sensor/SunSensorModel.hpp"
#include "sim/Constants.hpp"
#include "sim/DynamicsParams.hpp"
#include "sim/KeplerOrbit.hpp"
#include "sim/SunEphemeris.hpp"
#include "tests/support/TestUnits.hpp"

using flatsat::estimator::chiSquareQuantile;
using flatsat::estimator::MeasurementUse;
using flatsat::estimator::Mekf;
using flatsat::estimator::MekfInput;
using flatsat::estimator::MekfParams;
using flatsat::onboard::ReferenceModel;

namespace {

constexpr double kDegPerHour = kDeg / 3600.0;

// Datasheet-typical sensors (the default scenario's): a navigation-grade gyro (ARW 0.01°/√h,
// bias 0.5°/h), a fluxgate magnetometer with 50 nT noise after calibration, a fine Sun sensor
// with 0.01° per axis and a 60° half-cone field of view.
constexpr double kArw = 2.9e-6;
constexpr double kRrw = 1.0e-9;
constexpr double kMagNoise_T = 50e-9;
constexpr double kSunNoise_rad = 0.01 * kDeg;
constexpr double kTurnOnBiasSigma_rad_s = 0.5 * kDegPerHour;

constexpr double kMagBiasSigma_T = 30e-9;

/// A turn-on bias drawn per run, 0.5°/h 1σ per axis (the filter's prior).
Eigen::Vector3d turnOnBias(std::uint64_t seed) {
  flatsat::GaussianNoise draws(seed);
  return draws.vector<3>(kTurnOnBiasSigma_rad_s);
}

/// A magnetometer bias left after calibration, drawn per run, 30 nT 1σ per axis (the prior).
Eigen::Vector3d residualMagnetometerBias(std::uint64_t seed) {
  flatsat::GaussianNoise draws(seed + 1000);
  return draws.vector<3>(kMagBiasSigma_T);
}

// χ² bounds of a single sample (two-sided 95 %): χ²_ν(0.025), χ²_ν(0.975) from the published
// tables (Abramowitz & Stegun Table 26.8).
// Monte Carlo NEES test (Bar-Shalom, Li & Kirubarajan 2001, Estimation with Applications to
// Tracking and Navigation, §5.4.2): over R runs, R·mean(NEES) ~ χ²_nR (n = 9 states), so the
// mean lies in [χ²_nR(0.025), χ²_nR(0.975)] / R with 95 % probability.
constexpr int kRuns = 40;

/// P(χ²_2m ≤ x) = 1 − e^(−x/2) Σ_{j<m} (x/2)^j / j! (Abramowitz & Stegun 26.4.21).
double chiSquareEvenCdf(int dof, double x) {
  double term = 1.0, sum = 0.0;
  for (int j = 0; j < dof / 2; ++j) {
    sum += term;
    term *= 0.5 * x / (j + 1);
  }
  return 1.0 - std::exp(-0.5 * x) * sum;
}

double chiSquareEvenQuantile(int dof, double p) {
  double lo = 0.0, hi = 10.0 * dof + 100.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (chiSquareEvenCdf(dof, mid) < p ? lo : hi) = mid;
  }
  return lo;
}

flatsat::onboard::ReferenceModelParams orbitParams() {
  flatsat::onboard::ReferenceModelParams p;
  p.epoch = {2026, 3, 20, 0, 0, 0.0};
  p.orbit.semi_major_axis_m = flatsat::sim::kEarthEquatorialRadius_m + 560e3;
  p.orbit.inclination_rad = 53.0 * kDeg;
  p.orbit.raan_rad = 40.0 * kDeg;
  return p;
}

MekfParams filterParams() {
  MekfParams p;
  p.gyro_arw_rad_per_sqrt_s = kArw;
  p.gyro_rrw_rad_per_s_sqrt_s = kRrw;
  p.sun_sigma_rad = kSunNoise_rad;
  p.magnetometer_noise_T = kMagNoise_T;
  p.field_model_sigma_rad = 0.0;  // the onboard model is the truth's here
  p.initial_attitude_sigma_rad = 1.0 * kDeg;
  p.initial_bias_sigma_rad_s = kTurnOnBiasSigma_rad_s;
  p.magnetometer_bias_sigma_T = kMagBiasSigma_T;
  return p;
}

/// Rotation by |w|·dt about w, written with Eigen's AngleAxis (not the filter's exponential).
Eigen::Quaterniond rotate(const Eigen::Vector3d& w, double dt) {
  const double n = w.norm();
  return n > 0.0 ? Eigen::Quaterniond(Eigen::AngleAxisd(n * dt, w / n)) : Eigen::Quaterniond::Identity();
}

/// Error rotation vector δθ with q_true = q_est ⊗ exp(δθ/2).
Eigen::Vector3d attitudeError(const Eigen::Quaterniond& q_est, const Eigen::Quaterniond& q_true) {
  const Eigen::AngleAxisd aa(q_est.conjugate() * q_true);
  const double angle = aa.angle() > std::numbers::pi ? aa.angle() - 2.0 * std::numbers::pi : aa.angle();
  return angle * aa.axis();
}

struct Sample {
  double t_s;
  bool sunlit;
  double error_rad;      // |δθ|
  double nees;           // normalised estimation error squared of all 9 states
  double sigma_max_rad;  // largest attitude 1σ of the published covariance
  double sigma_yz_rad;   // larger 1σ of the axes ⊥ the Sun (body y, z), the ones the Sun fixes
  Eigen::Vector3d bias_error_rad_s;
  Mekf::Output out;
};

/// The spacecraft holds body +x near the Sun and rolls about it at 0.3°/s with a slow
/// wobble of the other axes (≈ 1°), so every axis is excited and the Sun stays in view.
struct Spacecraft {
  ReferenceModel reference{orbitParams()};
  flatsat::sim::KeplerOrbit orbit{orbitParams().orbit};
  double jd0 = flatsat::sim::julianDate(orbitParams().epoch);
  std::uint64_t seed;
  flatsat::gyro::GyroModel gyro{{kArw, kRrw, turnOnBias(seed), seed + 1}};
  Eigen::Vector3d mag_bias_T = residualMagnetometerBias(seed);
  flatsat::magnetometer::MagnetometerModel magnetometer{{kMagNoise_T, mag_bias_T,
                                                         Eigen::Vector3d::Ones(), 0.0, 1e-4, seed + 2}};
  flatsat::sun_sensor::SunSensorModel sun_sensor{
      {Eigen::Vector3d::UnitX(), kSunNoise_rad, 60.0 * kDeg, 0.5, seed + 3}};
  Mekf filter;
  Eigen::Quaterniond q_true;
  std::int64_t t_ns = 0;

  // Fault injection, in simulated seconds.
  double magnetometer_lost_from_s = -1.0, magnetometer_lost_to_s = -1.0;
  double star_tracker_sigma_rad = 0.0;  // 0: no star tracker
  std::vector<double> outlier_times_s;

  explicit Spacecraft(std::uint64_t seed_ = 10, const MekfParams& params = filterParams())
      : seed(seed_), filter(params) {
    // +x on the Sun at t = 0, rolled arbitrarily.
    const Eigen::Vector3d s_N = reference.step(0).sun_N_unit;
    q_true = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), s_N) *
             Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()));
  }

  static Eigen::Vector3d rate(double t) {
    const double wobble = 2.0 * std::numbers::pi / 600.0;
    return {0.3 * kDeg, 1e-4 * std::sin(wobble * t), 1e-4 * std::cos(1.3 * wobble * t)};
  }

  double illumination(double t_s) const {
    const double jd_tt = jd0 + (t_s + flatsat::sim::kTtMinusUtc_s) / 86400.0;
    return flatsat::sim::illumination(orbit.at(t_s).r_N_m, flatsat::sim::sunPosition_N_m(jd_tt));
  }

  bool isOutlier(double t_s) const {
    return std::any_of(outlier_times_s.begin(), outlier_times_s.end(),
                       [&](double o) { return std::abs(o - t_s) < 0.5 * kStep10Hz_s; });
  }

  /// Samples every step over `seconds`; the first call also takes the sample at t = 0.
  std::vector<Sample> run(double seconds) {
    std::vector<Sample> samples;
    if (!started_) {
      started_ = true;
      samples.push_back(sample(rate(0.0)));
    }
    for (auto k = std::lround(seconds / kStep10Hz_s); k > 0; --k) {
      // Truth moves with the rate held over the step, which is what a mean-rate gyro reports.
      const Eigen::Vector3d w = rate(static_cast<double>(t_ns) * 1e-9);
      q_true = q_true * rotate(w, kStep10Hz_s);
      t_ns += kStep10Hz_ns;
      samples.push_back(sample(w));
    }
    return samples;
  }

 private:
  bool started_ = false;
  flatsat::GaussianNoise star_draws_{seed + 4};

  Sample sample(const Eigen::Vector3d& w) {
    const double t = static_cast<double>(t_ns) * 1e-9;
    const auto ref = reference.step(t_ns);
    const auto g = gyro.step({w}, t_ns);

    MekfInput in;
    in.w_gyro_B_rad_s = g.w_NB_B_rad_s;
    const auto sun = sun_sensor.step({q_true.conjugate() * ref.sun_N_unit, illumination(t)}, t_ns);
    in.sun_B_meas_unit = sun.sun_B_unit;
    in.sun_valid = sun.valid;
    in.b_B_meas_T = magnetometer.step({q_true.conjugate() * ref.b_N_T}, t_ns).b_B_T;
    in.b_valid = !(t >= magnetometer_lost_from_s && t < magnetometer_lost_to_s);
    if (isOutlier(t)) {
      // A 30° Sun glint and a 20 µT field spike in the same sample.
      in.sun_B_meas_unit = Eigen::AngleAxisd(30.0 * kDeg, Eigen::Vector3d::UnitY()) * in.sun_B_meas_unit;
      in.b_B_meas_T += Eigen::Vector3d(0.0, 2e-5, 0.0);
    }
    if (star_tracker_sigma_rad > 0.0) {
      in.q_NB_star = q_true * rotate(star_draws_.vector<3>(star_tracker_sigma_rad), 1.0);
      in.star_valid = true;
    }
    in.sun_N_ref_unit = ref.sun_N_unit;
    in.b_N_ref_T = ref.b_N_T;

    Sample s;
    s.t_s = t;
    s.sunlit = sun.valid;
    s.out = filter.step(in, t_ns);
    flatsat::estimator::MekfVector e;
    e.head<3>() = attitudeError(s.out.q_NB, q_true);
    e.segment<3>(3) = g.bias_B_rad_s - s.out.gyro_bias_B_rad_s;
    e.tail<3>() = mag_bias_T - s.out.magnetometer_bias_B_T;
    s.error_rad = e.head<3>().norm();
    s.bias_error_rad_s = e.segment<3>(3);
    s.nees = s.out.initialized ? e.dot(s.out.covariance.ldlt().solve(e)) : 0.0;
    s.sigma_max_rad = std::sqrt(s.out.covariance.topLeftCorner<3, 3>().diagonal().maxCoeff());
    s.sigma_yz_rad = std::sqrt(std::max(s.out.covariance(1, 1), s.out.covariance(2, 2)));
    return s;
  }
};

/// 3·RMS of |δθ| over the samples that pass `keep`: a bound on the total error angle that
/// holds ≥ 99.7 % of the time for a Gaussian error.
template <class Keep>
double threeSigma(const std::vector<Sample>& samples, Keep keep) {
  double sum = 0.0;
  int n = 0;
  for (const auto& s : samples) {
    if (!keep(s)) continue;
    sum += s.error_rad * s.error_rad;
    ++n;
  }
  REQUIRE(n > 0);
  return 3.0 * std::sqrt(sum / n);
}

}  // namespace
TEST_CASE("MEKF gates sit at the published chi-square quantiles", "[estimator][mekf]") {
  // Abramowitz & Stegun Table 26.8.
  CHECK(chiSquareQuantile(2, 0.95) == Approx(5.9915).epsilon(1e-4));
  CHECK(chiSquareQuantile(2, 0.99) == Approx(9.2103).epsilon(1e-4));
  CHECK(chiSquareQuantile(3, 0.95) == Approx(7.8147).epsilon(1e-4));
  CHECK(chiSquareQuantile(3, 0.999) == Approx(16.266).epsilon(1e-4));
  const Mekf filter(filterParams());
  CHECK(filter.gate2() == Approx(chiSquareQuantile(2, 0.9999)));
  CHECK(filter.gate3() == Approx(chiSquareQuantile(3, 0.9999)));
}

TEST_CASE("MEKF parameters are validated field by field", "[estimator][mekf]") {
  CHECK(MekfParams{}.validate().empty());
  MekfParams p;
  p.gyro_arw_rad_per_sqrt_s = 0.0;
  p.star_tracker_sigma_B_rad.z() = -1.0;
  p.gate_probability = 1.0;
  p.reacquire_after_rejections = 0;
  const auto errors = p.validate();
  REQUIRE(errors.size() == 4);
  CHECK(errors[0].rfind("gyro_arw_rad_per_sqrt_s:", 0) == 0);
  CHECK(errors[1].rfind("star_tracker_sigma_B_rad:", 0) == 0);
  CHECK(errors[2].rfind("gate_probability:", 0) == 0);
  CHECK(errors[3].rfind("reacquire_after_rejections:", 0) == 0);
  CHECK_THROWS_AS(Mekf(p), std::invalid_argument);
}

TEST_CASE("MEKF starts invalid and initialises by TRIAD or from the star tracker", "[estimator][mekf]") {
  Mekf filter(filterParams());
  const Eigen::Quaterniond q(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()));
  const Eigen::Vector3d s_N = Eigen::Vector3d(0.3, 0.9, 0.2).normalized();
  const Eigen::Vector3d b_N(1.5e-5, -2.0e-5, 3.5e-5);
  MekfInput in;
  in.sun_N_ref_unit = s_N;
  in.b_N_ref_T = b_N;
  in.sun_B_meas_unit = q.conjugate() * s_N;
  in.sun_valid = true;
  in.b_B_meas_T = q.conjugate() * b_N;
  WHEN("only the Sun is seen") {
    const auto out = filter.step(in, 0);
    THEN("there is no estimate, and it says so") {
      CHECK_FALSE(out.initialized);
      CHECK_FALSE(out.valid);
    }
  }
  WHEN("Sun and field are seen") {
    in.b_valid = true;
    const auto out = filter.step(in, 0);
    THEN("TRIAD gives the attitude and the covariance is the configured one") {
      CHECK(out.valid);
      CHECK(out.q_NB.angularDistance(q) < 1e-12);
      CHECK(out.covariance(0, 0) == Approx(std::pow(filterParams().initial_attitude_sigma_rad, 2)));
      CHECK(out.covariance(5, 5) == Approx(std::pow(filterParams().initial_bias_sigma_rad_s, 2)));
    }
  }
  WHEN("only a star tracker is seen") {
    in.sun_valid = false;
    in.q_NB_star = q;
    in.star_valid = true;
    const auto out = filter.step(in, 0);
    THEN("its attitude is taken") {
      CHECK(out.valid);
      CHECK(out.star == MeasurementUse::kUsed);
      CHECK(out.q_NB.angularDistance(q) < 1e-12);
    }
  }
}

TEST_CASE("MEKF with gyro, magnetometer and Sun sensor: accurate in sunlight, bias converged",
          "[estimator][mekf]") {
  Spacecraft sc;
  const double orbit_s = sc.orbit.period_s();
  const auto samples = sc.run(2.0 * orbit_s);
  // Attitude in sunlight once the TRIAD transient (1° initial σ) has settled.
  const double error_3sigma =
      threeSigma(samples, [](const Sample& s) { return s.sunlit && s.t_s > 600.0; });
  INFO("attitude error 3σ in sunlight [deg] " << error_3sigma / kDeg);
  CHECK(error_3sigma < 0.5 * kDeg);
  CHECK(std::all_of(samples.begin(), samples.end(), [](const Sample& s) { return s.out.valid; }));

  // Bias converged within one orbit: from then on every axis within 0.05°/h, a tenth of the
  // turn-on bias's 1σ, and the published 1σ below 0.02°/h.
  double bias_error_max = 0.0;
  double bias_sigma_max = 0.0;
  for (const auto& s : samples) {
    if (s.t_s < orbit_s) continue;
    bias_error_max = std::max(bias_error_max, s.bias_error_rad_s.cwiseAbs().maxCoeff());
    bias_sigma_max = std::max(
        bias_sigma_max, std::sqrt(s.out.covariance.block<3, 3>(3, 3).diagonal().maxCoeff()));
  }
  INFO("bias error after one orbit [deg/h] " << bias_error_max / kDegPerHour);
  CHECK(bias_error_max < 0.05 * kDegPerHour);
  CHECK(bias_sigma_max < 0.02 * kDegPerHour);
  // The gate refuses about 1 - gate_probability of the good measurements, no more.
  CHECK(samples.back().out.rejected_total < 4 * samples.size() * 2 * 1e-4 + 5);
}

TEST_CASE("a restarted MEKF given the old one's state goes on exactly as if never stopped", "[estimator][mekf][restart]") {
  Spacecraft uninterrupted, restarted;
  uninterrupted.magnetometer_lost_from_s = restarted.magnetometer_lost_from_s = 2500.0;
  uninterrupted.magnetometer_lost_to_s = restarted.magnetometer_lost_to_s = 2700.0;
  uninterrupted.outlier_times_s = restarted.outlier_times_s = {1500.0, 2000.0};
  uninterrupted.run(1200.0);
  restarted.run(1200.0);
  const flatsat::estimator::MekfState checkpoint = restarted.filter.state();
  REQUIRE(checkpoint.initialized);
  restarted.filter = Mekf(filterParams());
  restarted.filter.restore(checkpoint);
  const auto a = uninterrupted.run(2400.0);  // through outliers, a magnetometer outage and eclipse
  const auto b = restarted.run(2400.0);
  REQUIRE(a.size() == b.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    differing += a[i].out.q_NB.coeffs() != b[i].out.q_NB.coeffs() || a[i].out.covariance != b[i].out.covariance ||
                 a[i].out.gyro_bias_B_rad_s != b[i].out.gyro_bias_B_rad_s ||
                 a[i].out.rejected_total != b[i].out.rejected_total;
  }
  CHECK(differing == 0);
  CHECK(b.back().out.rejected_total >= 2);  // the outliers counted on from the old count

  // Steps missed while the process was down: propagated over the gap in one go, the
  // attitude uncertainty grows by the gyro's random walks (Farrenkopf), about ARW²·Δt per
  // axis (the rotation of the error axes over the gap leaves the trace alone).
  Mekf late(filterParams());
  late.restore(checkpoint);
  MekfInput coast;
  coast.w_gyro_B_rad_s = Spacecraft::rate(0.0);
  const double gap_s = 30.0;
  const auto out = late.step(coast, checkpoint.last_t_ns + std::llround(gap_s * 1e9));
  const double grown = out.covariance.topLeftCorner<3, 3>().trace() - checkpoint.P.topLeftCorner<3, 3>().trace();
  CHECK(grown > 0.9 * 3.0 * kArw * kArw * gap_s);
}

TEST_CASE("MEKF covariance is consistent: Monte Carlo NEES inside its 95 % bounds", "[estimator][mekf]") {
  // Runs with their own sensor noise, gyro turn-on bias and magnetometer residual bias; per
  // time step the NEES of the full 9-state error averaged over the runs, bounds from the
  // closed form.
  constexpr int n = flatsat::estimator::kMekfStates;
  const double low = chiSquareEvenQuantile(n * kRuns, 0.025) / kRuns;
  const double high = chiSquareEvenQuantile(n * kRuns, 0.975) / kRuns;
  // A&S Table 26.8 at 60 degrees of freedom checks the closed form.
  REQUIRE(chiSquareEvenQuantile(60, 0.025) == Approx(40.4817).epsilon(1e-5));
  REQUIRE(chiSquareEvenQuantile(60, 0.975) == Approx(83.2976).epsilon(1e-5));
  std::vector<std::vector<Sample>> runs;
  for (int r = 0; r < kRuns; ++r) {
    Spacecraft sc(100 + 10 * static_cast<std::uint64_t>(r));
    runs.push_back(sc.run(sc.orbit.period_s()));
  }
  int inside = 0, counted = 0;
  double sum = 0.0;
  for (std::size_t k = 0; k < runs[0].size(); ++k) {
    if (runs[0][k].t_s < 60.0) continue;  // TRIAD's initial 1° σ is deliberately conservative
    double mean = 0.0;
    for (const auto& run : runs) mean += run[k].nees / kRuns;
    inside += mean >= low && mean <= high;
    sum += mean;
    ++counted;
  }
  const double fraction = static_cast<double>(inside) / counted;
  INFO("mean NEES " << sum / counted << ", fraction inside [" << low << ", " << high
                    << "]: " << fraction);
  CHECK(fraction >= 0.95);
}

TEST_CASE("MEKF with a star tracker holds the attitude within 0.02° (3σ)", "[estimator][mekf]") {
  Spacecraft sc;
  sc.star_tracker_sigma_rad = 10.0 / 3600.0 * kDeg;  // 10 arcsec 1σ per axis, a typical tracker
  MekfParams p = filterParams();
  p.star_tracker_sigma_B_rad.setConstant(sc.star_tracker_sigma_rad);
  sc.filter = Mekf(p);
  const auto samples = sc.run(sc.orbit.period_s());
  const double error_3sigma = threeSigma(samples, [](const Sample& s) { return s.t_s > 60.0; });
  INFO("attitude error 3σ with star tracker [deg] " << error_3sigma / kDeg);
  CHECK(error_3sigma < 0.02 * kDeg);
  CHECK(samples.back().out.star == MeasurementUse::kUsed);
}

TEST_CASE("MEKF rides through eclipse: covariance grows without the Sun and recovers", "[estimator][mekf]") {
  Spacecraft sc;
  const auto samples = sc.run(sc.orbit.period_s());
  // The first eclipse of the orbit: last sunlit sample before it, last one in it.
  const auto entry = std::adjacent_find(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) {
    return a.sunlit && !b.sunlit;
  });
  REQUIRE(entry != samples.end());
  const auto exit = std::adjacent_find(entry + 1, samples.end(), [](const Sample& a, const Sample& b) {
    return !a.sunlit && b.sunlit;
  });
  REQUIRE(exit != samples.end());
  INFO("eclipse " << entry->t_s << " s to " << exit->t_s << " s; σ ⊥ Sun before " << entry->sigma_yz_rad
                  << ", at the end " << exit->sigma_yz_rad << ", 300 s after " << (exit + 3000)->sigma_yz_rad);
  CHECK(exit->sigma_yz_rad > 3.0 * entry->sigma_yz_rad);  // degrades ...
  // ... but stays a valid, consistent estimate on field and gyro alone,
  CHECK(std::all_of(entry, exit, [](const Sample& s) { return s.out.valid; }));
  CHECK(std::all_of(entry, exit, [](const Sample& s) { return s.error_rad < 4.0 * s.sigma_max_rad; }));
  // and recovers once the Sun is back.
  CHECK((exit + 3000)->sigma_yz_rad < 1.5 * entry->sigma_yz_rad);
  CHECK((exit + 3000)->error_rad < 0.5 * kDeg / 3.0);
}

TEST_CASE("MEKF rides through a magnetometer fault and recovers", "[estimator][mekf]") {
  Spacecraft sc;
  sc.magnetometer_lost_from_s = 600.0;
  sc.magnetometer_lost_to_s = 1200.0;
  const auto samples = sc.run(1500.0);
  const auto at = [&](double t) { return samples[static_cast<std::size_t>(std::lround(t / kStep10Hz_s))]; };
  REQUIRE(at(1200.0).sunlit);  // the fault is in sunlight: only the roll about the Sun is lost
  CHECK(at(600.0).out.field == MeasurementUse::kAbsent);
  // The roll about the Sun line is only seen by the field: its σ grows with the gyro's ARW ...
  CHECK(at(1199.9).sigma_max_rad > 2.0 * at(599.9).sigma_max_rad);
  CHECK(std::all_of(samples.begin() + 6000, samples.begin() + 12000,
                    [](const Sample& s) { return s.out.valid && s.error_rad < 4.0 * s.sigma_max_rad; }));
  // ... and shrinks again once the field is back.
  CHECK(at(1200.0).out.field == MeasurementUse::kUsed);
  CHECK(at(1500.0).sigma_max_rad < 1.5 * at(599.9).sigma_max_rad);
}

TEST_CASE("MEKF gate rejects outliers and counts them", "[estimator][mekf]") {
  Spacecraft reference;
  const auto clean = reference.run(1500.0);
  Spacecraft sc;
  sc.outlier_times_s = {700.0, 900.0, 1100.0, 1300.0};
  const auto samples = sc.run(1500.0);
  for (const double t : sc.outlier_times_s) {
    const auto& s = samples[static_cast<std::size_t>(std::lround(t / kStep10Hz_s))];
    CHECK(s.out.sun == MeasurementUse::kRejected);
    CHECK(s.out.field == MeasurementUse::kRejected);
  }
  CHECK(samples.back().out.rejected_total == clean.back().out.rejected_total + 8);
  // The outliers left no trace: the estimate is the clean run's.
  const double error_3sigma = threeSigma(samples, [](const Sample& s) { return s.t_s > 600.0; });
  const double clean_3sigma = threeSigma(clean, [](const Sample& s) { return s.t_s > 600.0; });
  CHECK(error_3sigma < 1.01 * clean_3sigma);
}

TEST_CASE("MEKF calls its estimate invalid when the covariance outgrows the limit", "[estimator][mekf]") {
  MekfParams p = filterParams();
  p.max_attitude_sigma_rad = 0.1 * kDeg;
  Spacecraft sc(10, p);
  sc.magnetometer_lost_from_s = 100.0;
  sc.magnetometer_lost_to_s = 1e9;
  const auto samples = sc.run(1500.0);
  INFO("σ at 100 s " << samples[1000].sigma_max_rad << ", at 1500 s " << samples.back().sigma_max_rad);
  CHECK(samples[1000].out.valid);
  CHECK_FALSE(samples.back().out.valid);  // roll about the Sun unobserved for 1400 s
  CHECK(samples.back().out.initialized);
}

TEST_CASE("MEKF re-acquires by TRIAD when one sensor is gated out for too long", "[estimator][mekf]") {
  Spacecraft sc;
  sc.run(300.0);
  // The body turns 5° about y between two samples without the gyro seeing it (a stuck-gyro
  // episode, say): Sun and field now disagree with the estimate by far more than the gate.
  sc.q_true = sc.q_true * Eigen::Quaterniond(Eigen::AngleAxisd(5.0 * kDeg, Eigen::Vector3d::UnitY()));
  const auto samples = sc.run(60.0);
  const auto gap = std::find_if(samples.begin(), samples.end(),
                                [](const Sample& s) { return s.out.sun == MeasurementUse::kUsed; });
  REQUIRE(gap != samples.end());
  const auto rejected_steps = gap - samples.begin();
  INFO("steps until the Sun is used again: " << rejected_steps);
  // 100 rejections in a row, then TRIAD at the next step.
  CHECK(rejected_steps == filterParams().reacquire_after_rejections);
  CHECK(samples.front().out.sun == MeasurementUse::kRejected);
  // Converged again: the error is as small as the filter's own covariance says
  // (the bound the other MEKF cases use), well below the 5° jump.
  INFO("error " << samples.back().error_rad / kDeg << "°, σ " << samples.back().sigma_max_rad / kDeg << "°");
  CHECK(samples.back().error_rad < 4.0 * samples.back().sigma_max_rad);
  CHECK(samples.back().error_rad < 0.1 * 5.0 * kDeg);
  CHECK(samples.back().out.valid);
}
