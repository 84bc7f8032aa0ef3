// SPDX-License-Identifier: Apache-2.0
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "components/estimator/AttitudeEstimator.hpp"
#include "tests/support/TestUnits.hpp"

using flatsat::estimator::AttitudeEstimator;
using flatsat::estimator::AttitudeEstimatorInput;
using flatsat::estimator::AttitudeEstimatorParams;
using flatsat::estimator::triad;

namespace {

const Eigen::Vector3d kSun_N = Eigen::Vector3d(0.3, 0.9, 0.2).normalized();
const Eigen::Vector3d kField_N_T(1.5e-5, -2.0e-5, 3.5e-5);
const Eigen::Quaterniond kAttitude0_NB(Eigen::AngleAxisd(1.0, Eigen::Vector3d(1.0, -1.0, 2.0).normalized()));

/// Rotation by |w|·dt about w: the truth's attitude increment, written with Eigen's
/// AngleAxis so it does not share code with the estimator.
Eigen::Quaterniond rotate(const Eigen::Vector3d& w, double dt) {
  const double n = w.norm();
  return n > 0.0 ? Eigen::Quaterniond(Eigen::AngleAxisd(n * dt, w / n)) : Eigen::Quaterniond::Identity();
}

/// Sensor readings of an exact Sun and field seen from attitude q_NB.
AttitudeEstimatorInput measure(const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& w_gyro, bool sun,
                               bool field) {
  AttitudeEstimatorInput in;
  in.w_gyro_B_rad_s = w_gyro;
  in.sun_B_meas_unit = sun ? Eigen::Vector3d(q_NB.conjugate() * kSun_N) : Eigen::Vector3d::Zero();
  in.sun_valid = sun;
  in.b_B_meas_T = q_NB.conjugate() * kField_N_T;
  in.b_valid = field;
  in.sun_N_ref_unit = kSun_N;
  in.b_N_ref_T = kField_N_T;
  return in;
}

/// A tumbling body (rates of a few hundredths of rad/s on all axes) seen by a biased,
/// noise-free gyro; the rate is held over each step, which is what a gyro sample means.
struct EstimatorScenario {
  AttitudeEstimator estimator;
  Eigen::Quaterniond q_true = kAttitude0_NB;
  Eigen::Vector3d bias_true;
  std::int64_t t_ns = 0;
  AttitudeEstimator::Output out;

  EstimatorScenario(const AttitudeEstimatorParams& p, const Eigen::Vector3d& bias)
      : estimator(p), bias_true(bias) {
    out = estimator.step(measure(q_true, rate(0.0) + bias_true, true, true), t_ns);
  }

  static Eigen::Vector3d rate(double t) {
    return {0.02 * std::sin(0.01 * t), 0.015, -0.01 * std::cos(0.013 * t)};
  }

  void run(double seconds, bool sun, bool field) {
    for (int k = 0; k < static_cast<int>(std::lround(seconds / kStep10Hz_s)); ++k) {
      const Eigen::Vector3d w = rate(static_cast<double>(t_ns) * 1e-9);
      q_true = q_true * rotate(w, kStep10Hz_s);
      t_ns += kStep10Hz_ns;
      out = estimator.step(measure(q_true, w + bias_true, sun, field), t_ns);
    }
  }

  double attitudeError() const { return out.q_NB.angularDistance(q_true); }
  double biasError() const { return (out.gyro_bias_B_rad_s - bias_true).norm(); }
};

}  // namespace

TEST_CASE("TRIAD recovers a known attitude exactly from noise-free vectors", "[components][estimator]") {
  const Eigen::Quaterniond q_true(Eigen::AngleAxisd(2.5, Eigen::Vector3d(-1.0, 2.0, 0.5).normalized()));
  const Eigen::Vector3d s_B = q_true.conjugate() * kSun_N;
  const Eigen::Vector3d b_B = q_true.conjugate() * kField_N_T;
  Eigen::Quaterniond q;
  REQUIRE(triad(s_B, b_B, kSun_N, kField_N_T, q));
  CHECK(q.angularDistance(q_true) < 1e-12);

  GIVEN("a field measurement 2° off its model") {
    const Eigen::Vector3d b_bad_B = Eigen::AngleAxisd(2.0 * kDeg, Eigen::Vector3d::UnitZ()) * b_B;
    REQUIRE(triad(s_B, b_bad_B, kSun_N, kField_N_T, q));
    THEN("the primary (Sun) is still matched exactly and the error stays below 2°") {
      CHECK((q * s_B - kSun_N).norm() < 1e-12);
      CHECK(q.angularDistance(q_true) <= 2.0 * kDeg + 1e-12);
    }
  }
  GIVEN("a field parallel to the Sun") {
    Eigen::Quaterniond untouched(0.0, 1.0, 0.0, 0.0);
    THEN("TRIAD refuses and leaves the output alone") {
      CHECK_FALSE(triad(s_B, 3e-5 * s_B, kSun_N, kField_N_T, untouched));
      CHECK(untouched.coeffs() == Eigen::Quaterniond(0.0, 1.0, 0.0, 0.0).coeffs());
    }
  }
}

TEST_CASE("Estimator initialises with TRIAD only from a valid Sun + field pair", "[components][estimator]") {
  AttitudeEstimator est(AttitudeEstimatorParams{});
  WHEN("only the Sun is valid") {
    const auto out = est.step(measure(kAttitude0_NB, Eigen::Vector3d::Zero(), true, false), 0);
    THEN("it stays uninitialised, identity, with no Sun estimate") {
      CHECK_FALSE(out.initialized);
      CHECK(out.q_NB.coeffs() == Eigen::Quaterniond::Identity().coeffs());
      CHECK(out.sun_B_est_unit == Eigen::Vector3d::Zero());
    }
  }
  WHEN("both vectors are valid") {
    const auto out = est.step(measure(kAttitude0_NB, Eigen::Vector3d::Zero(), true, true), 0);
    THEN("the attitude is exact and both vectors are reported as used") {
      CHECK(out.initialized);
      CHECK(out.sun_used);
      CHECK(out.field_used);
      CHECK(out.q_NB.angularDistance(kAttitude0_NB) < 1e-12);
      CHECK((out.sun_B_est_unit - kAttitude0_NB.conjugate() * kSun_N).norm() < 1e-12);
    }
    AND_WHEN("reset") {
      est.reset();
      THEN("a Sun-only sample no longer suffices") {
        CHECK_FALSE(est.step(measure(kAttitude0_NB, Eigen::Vector3d::Zero(), true, false), 1).initialized);
      }
    }
  }
}

TEST_CASE("Estimator integrates the gyro with the exact exponential", "[components][estimator]") {
  AttitudeEstimator est(AttitudeEstimatorParams{});
  est.step(measure(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero(), true, true), 0);
  // Large steps and a fast constant rate: any truncated series would show.
  const Eigen::Vector3d w(0.3, -0.2, 0.5);
  AttitudeEstimator::Output out;
  for (int k = 1; k <= 8; ++k) {
    out = est.step(measure(Eigen::Quaterniond::Identity(), w, false, false), k * 500'000'000LL);
  }
  CHECK_FALSE(out.sun_used);
  CHECK_FALSE(out.field_used);
  CHECK(out.q_NB.angularDistance(rotate(w, 4.0)) < 1e-12);
  CHECK(out.w_NB_B_rad_s == w);
}

TEST_CASE("Estimator converges on a constant gyro bias", "[components][estimator]") {
  const Eigen::Vector3d bias(2e-3, -1e-3, 1.5e-3);
  EstimatorScenario s(AttitudeEstimatorParams{}, bias);
  REQUIRE(s.out.initialized);
  s.run(300.0, true, true);
  const double bias_error_300s = s.biasError();
  s.run(1200.0, true, true);
  CHECK(s.biasError() < 0.01 * bias_error_300s);
  CHECK(s.biasError() < 1e-6);
  CHECK(s.attitudeError() < 1e-5);
  CHECK((s.out.w_NB_B_rad_s - EstimatorScenario::rate(static_cast<double>(s.t_ns - kStep10Hz_ns) * 1e-9)).norm() <
        1e-6);
  CHECK((s.out.sun_B_est_unit - s.q_true.conjugate() * kSun_N).norm() < 1e-5);

  GIVEN("an eclipse with no field either") {
    const double error_before = s.attitudeError();
    const Eigen::Vector3d bias_before = s.out.gyro_bias_B_rad_s;
    s.run(600.0, false, false);
    THEN("it coasts on the gyro with the bias frozen: error grows at most by |Δb|·T") {
      CHECK_FALSE(s.out.sun_used);
      CHECK_FALSE(s.out.field_used);
      CHECK(s.out.gyro_bias_B_rad_s == bias_before);
      CHECK(s.attitudeError() <= error_before + (bias_before - bias).norm() * 600.0 + 1e-9);
    }
  }
  GIVEN("an eclipse with the field still valid") {
    s.run(300.0, false, true);
    THEN("the field alone keeps correcting") {
      CHECK(s.out.field_used);
      CHECK_FALSE(s.out.sun_used);
      CHECK(s.attitudeError() < 1e-4);
    }
  }
}

TEST_CASE("Estimator does not overshoot after a long gap between samples", "[components][estimator]") {
  AttitudeEstimator est(AttitudeEstimatorParams{});  // k_P = 0.2/s: k_P·Δt = 20 over 100 s
  est.step(measure(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero(), true, true), 0);
  const Eigen::Quaterniond q_true = rotate(Eigen::Vector3d(0.05, -0.08, 0.03), 1.0);
  const auto out = est.step(measure(q_true, Eigen::Vector3d::Zero(), true, true), 100'000'000'000LL);
  // One step maps the error θ to (I − g·M)θ with M = 2I − s sᵀ − b bᵀ (eigenvalues in (0, 2)):
  // an unlimited g = 20 would multiply it, the ceiling g = ½ shrinks it.
  CHECK(out.q_NB.angularDistance(q_true) < Eigen::Quaterniond::Identity().angularDistance(q_true));
}

TEST_CASE("Estimator ignores the field when use_magnetometer is off", "[components][estimator]") {
  AttitudeEstimatorParams p;
  p.use_magnetometer = false;
  EstimatorScenario s(p, Eigen::Vector3d::Zero());
  REQUIRE(s.out.field_used);  // TRIAD still needs the pair
  s.run(1.0, true, true);
  CHECK(s.out.sun_used);
  CHECK_FALSE(s.out.field_used);
}

TEST_CASE("Estimator clamps the bias estimate", "[components][estimator]") {
  AttitudeEstimatorParams p;
  p.max_bias_rad_s = 5e-4;
  EstimatorScenario s(p, Eigen::Vector3d(2e-3, 0.0, 0.0));
  double worst = 0.0;
  for (int k = 0; k < 500; ++k) {
    s.run(1.0, true, true);
    worst = std::max(worst, s.out.gyro_bias_B_rad_s.cwiseAbs().maxCoeff());
  }
  CHECK(worst <= p.max_bias_rad_s);
  CHECK(s.out.gyro_bias_B_rad_s.x() == p.max_bias_rad_s);
  CHECK(s.out.bias_clamped);
}

TEST_CASE("Estimator params reject bad values", "[components][estimator]") {
  CHECK(AttitudeEstimatorParams{}.validate().empty());
  AttitudeEstimatorParams p;
  p.kp_per_s = -0.1;
  p.ki_per_s2 = std::numeric_limits<double>::quiet_NaN();
  p.max_bias_rad_s = 0.0;
  const auto errors = p.validate();
  REQUIRE(errors.size() == 3);
  CHECK(errors[0].rfind("kp_per_s:", 0) == 0);
  CHECK(errors[1].rfind("ki_per_s2:", 0) == 0);
  CHECK(errors[2].rfind("max_bias_rad_s:", 0) == 0);
  CHECK_THROWS_AS(AttitudeEstimator(p), std::invalid_argument);
}

TEST_CASE("estimator without a field source initialises from the Sun alone", "[estimator]") {
  AttitudeEstimatorParams p;
  p.sun_only_init = true;
  AttitudeEstimator filter(p);
  const Eigen::Quaterniond q_true =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()));
  const Eigen::Vector3d s_N = Eigen::Vector3d(0.3, 0.9, -0.2).normalized();
  AttitudeEstimatorInput in;
  in.sun_N_ref_unit = s_N;
  in.sun_B_meas_unit = q_true.conjugate() * s_N;
  in.sun_valid = true;  // no field at all
  const auto out = filter.step(in, 0);
  REQUIRE(out.initialized);
  CHECK((out.sun_B_est_unit - in.sun_B_meas_unit).norm() < 1e-12);
}

TEST_CASE("a restarted estimator given the old one's state goes on exactly as if never stopped",
          "[components][estimator][restart]") {
  const Eigen::Vector3d bias(2e-3, -1e-3, 1.5e-3);
  EstimatorScenario uninterrupted(AttitudeEstimatorParams{}, bias);
  EstimatorScenario restarted(AttitudeEstimatorParams{}, bias);
  uninterrupted.run(120.0, true, true);
  restarted.run(120.0, true, true);
  // Bias half learned: a fresh filter would start again from zero bias.
  REQUIRE(restarted.out.gyro_bias_B_rad_s.norm() > 0.1 * bias.norm());
  const AttitudeEstimator::State checkpoint = restarted.estimator.state();
  restarted.estimator = AttitudeEstimator(AttitudeEstimatorParams{});
  restarted.estimator.restore(checkpoint);
  for (int i = 0; i < 4; ++i) {  // through sunlight, eclipse, sunlight
    uninterrupted.run(150.0, i != 1, true);
    restarted.run(150.0, i != 1, true);
    CHECK(restarted.out.q_NB.coeffs() == uninterrupted.out.q_NB.coeffs());
    CHECK(restarted.out.gyro_bias_B_rad_s == uninterrupted.out.gyro_bias_B_rad_s);
  }
  // The same checkpoint on a fresh filter that missed 2 s of steps propagates over them.
  AttitudeEstimator late{AttitudeEstimatorParams{}};
  late.restore(checkpoint);
  const auto in = measure(restarted.q_true, Eigen::Vector3d::Zero(), false, false);
  const auto out = late.step(in, checkpoint.last_t_ns + 20 * kStep10Hz_ns);
  CHECK(out.initialized);
  CHECK(out.w_NB_B_rad_s.isApprox(-checkpoint.bias_B_rad_s));
  CHECK(out.q_NB.angularDistance(checkpoint.q_NB) == Approx(checkpoint.bias_B_rad_s.norm() * 2.0).epsilon(1e-9));
}
