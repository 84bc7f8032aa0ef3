// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include "components/gyro/GyroModel.hpp"
#include "tests/unit/components/SampleStats.hpp"
#include "tests/support/TestUnits.hpp"

using flatsat::gyro::GyroModel;
using flatsat::gyro::GyroParams;
using flatsat::test::checkGaussian;
using flatsat::test::SampleStats;

namespace {

const Eigen::Vector3d kRate_B_rad_s(0.01, -0.02, 0.005);

}  // namespace

TEST_CASE("Gyro first sample has no interval: truth plus initial bias", "[components][gyro]") {
  GyroParams p;
  p.angle_random_walk_rad_per_sqrt_s = 1e-3;
  p.rate_random_walk_rad_per_s_sqrt_s = 1e-4;
  p.bias0_B_rad_s = Eigen::Vector3d(1e-3, -2e-3, 3e-3);
  GyroModel gyro(p);
  const auto out = gyro.step({kRate_B_rad_s}, 5'000'000'000);
  CHECK(out.w_NB_B_rad_s == kRate_B_rad_s + p.bias0_B_rad_s);
  CHECK(out.bias_B_rad_s == p.bias0_B_rad_s);
  WHEN("the next call repeats the time stamp") {
    const auto again = gyro.step({kRate_B_rad_s}, 5'000'000'000);
    THEN("there is still no interval, hence no noise or drift") {
      CHECK(again.w_NB_B_rad_s == kRate_B_rad_s + p.bias0_B_rad_s);
    }
  }
}

TEST_CASE("Gyro white noise per sample is ARW/sqrt(dt)", "[components][gyro]") {
  GyroParams p;
  p.angle_random_walk_rad_per_sqrt_s = 2e-4;
  p.rate_random_walk_rad_per_s_sqrt_s = 0.0;
  p.bias0_B_rad_s = Eigen::Vector3d(1e-3, -2e-3, 5e-4);
  GyroModel gyro(p);
  GIVEN("a constant 10 Hz sample rate") {
    SampleStats stats[3];
    gyro.step({kRate_B_rad_s}, 0);
    for (int k = 1; k <= 20000; ++k) {
      const auto out = gyro.step({kRate_B_rad_s}, k * kStep10Hz_ns);
      REQUIRE(out.bias_B_rad_s == p.bias0_B_rad_s);  // no drift without RRW
      for (int i = 0; i < 3; ++i) {
        stats[i].add(out.w_NB_B_rad_s[i]);
      }
    }
    const double sigma = p.angle_random_walk_rad_per_sqrt_s / std::sqrt(kStep10Hz_s);
    for (int i = 0; i < 3; ++i) {
      checkGaussian(stats[i], kRate_B_rad_s[i] + p.bias0_B_rad_s[i], sigma);
    }
  }
  GIVEN("intervals alternating between 20 ms and 500 ms") {
    SampleStats fast;
    SampleStats slow;
    std::int64_t t_ns = 0;
    gyro.step({kRate_B_rad_s}, t_ns);
    for (int k = 0; k < 20000; ++k) {
      const bool is_fast = k % 2 == 0;
      t_ns += is_fast ? 20'000'000 : 500'000'000;
      const double error = gyro.step({kRate_B_rad_s}, t_ns).w_NB_B_rad_s.x() - kRate_B_rad_s.x() -
                           p.bias0_B_rad_s.x();
      (is_fast ? fast : slow).add(error);
    }
    THEN("each sample's sigma follows its own interval") {
      checkGaussian(fast, 0.0, p.angle_random_walk_rad_per_sqrt_s / std::sqrt(0.02));
      checkGaussian(slow, 0.0, p.angle_random_walk_rad_per_sqrt_s / std::sqrt(0.5));
    }
  }
}

TEST_CASE("Gyro bias is a random walk with RRW*sqrt(dt) steps", "[components][gyro]") {
  GyroParams p;
  p.angle_random_walk_rad_per_sqrt_s = 0.0;
  p.rate_random_walk_rad_per_s_sqrt_s = 3e-5;
  GyroModel gyro(p);
  SampleStats increments;
  SampleStats residual;  // ω̃ − ω − ½(β_k + β_{k−1}): the σ_u²Δt/12 part of the white noise
  Eigen::Vector3d bias_prev = gyro.step({kRate_B_rad_s}, 0).bias_B_rad_s;
  for (int k = 1; k <= 20000; ++k) {
    const auto out = gyro.step({kRate_B_rad_s}, k * kStep10Hz_ns);
    increments.add(out.bias_B_rad_s.y() - bias_prev.y());
    residual.add(out.w_NB_B_rad_s.y() - kRate_B_rad_s.y() - 0.5 * (out.bias_B_rad_s.y() + bias_prev.y()));
    bias_prev = out.bias_B_rad_s;
  }
  const double rrw = p.rate_random_walk_rad_per_s_sqrt_s;
  checkGaussian(increments, 0.0, rrw * std::sqrt(kStep10Hz_s));
  checkGaussian(residual, 0.0, rrw * std::sqrt(kStep10Hz_s / 12.0));
}

TEST_CASE("Gyro noise and bias replay from the seed", "[components][gyro]") {
  GyroParams p;
  p.angle_random_walk_rad_per_sqrt_s = 1e-4;
  p.rate_random_walk_rad_per_s_sqrt_s = 1e-5;
  p.bias0_B_rad_s = Eigen::Vector3d(1e-3, 0.0, 0.0);
  GyroModel a(p);
  GyroModel b(p);
  Eigen::Vector3d rates[10];
  Eigen::Vector3d biases[10];
  for (int k = 0; k < 10; ++k) {
    const auto out = a.step({kRate_B_rad_s}, k * kStep10Hz_ns);
    rates[k] = out.w_NB_B_rad_s;
    biases[k] = out.bias_B_rad_s;
    CHECK(b.step({kRate_B_rad_s}, k * kStep10Hz_ns).w_NB_B_rad_s == rates[k]);
  }
  CHECK(biases[9] != p.bias0_B_rad_s);
  WHEN("reset") {
    a.reset();
    THEN("the bias restarts at bias0 and the sequence repeats, time origin included") {
      for (int k = 0; k < 10; ++k) {
        const auto out = a.step({kRate_B_rad_s}, k * kStep10Hz_ns);
        CHECK(out.w_NB_B_rad_s == rates[k]);
        CHECK(out.bias_B_rad_s == biases[k]);
      }
    }
  }
}

TEST_CASE("Gyro params reject bad values", "[components][gyro]") {
  CHECK(GyroParams{}.validate().empty());
  GyroParams p;
  p.angle_random_walk_rad_per_sqrt_s = -1.0;
  p.rate_random_walk_rad_per_s_sqrt_s = std::numeric_limits<double>::infinity();
  p.bias0_B_rad_s.z() = std::numeric_limits<double>::quiet_NaN();
  const auto errors = p.validate();
  REQUIRE(errors.size() == 3);
  CHECK(errors[0].rfind("angle_random_walk_rad_per_sqrt_s:", 0) == 0);
  CHECK(errors[1].rfind("rate_random_walk_rad_per_s_sqrt_s:", 0) == 0);
  CHECK(errors[2].rfind("bias0_B_rad_s:", 0) == 0);
  CHECK_THROWS_AS(GyroModel(p), std::invalid_argument);
}

namespace {

/// Overlapping Allan deviation of rate samples at cluster size m (IEEE Std 952-1997, Annex C):
/// σ²(τ) = Σ (θ_{k+2m} − 2θ_{k+m} + θ_k)² / (2τ²(N − 2m)), θ the integrated angle.
double allanDeviation(const std::vector<double>& rate, double dt_s, std::size_t m) {
  std::vector<double> theta(rate.size() + 1, 0.0);
  for (std::size_t k = 0; k < rate.size(); ++k) theta[k + 1] = theta[k] + rate[k] * dt_s;
  const std::size_t n = theta.size();
  double sum = 0.0;
  for (std::size_t k = 0; k + 2 * m < n; ++k) {
    const double d = theta[k + 2 * m] - 2.0 * theta[k + m] + theta[k];
    sum += d * d;
  }
  const double tau = static_cast<double>(m) * dt_s;
  return std::sqrt(sum / (2.0 * tau * tau * static_cast<double>(n - 2 * m)));
}

std::vector<double> stationaryRates(const GyroParams& p, double dt_s, int samples) {
  GyroModel gyro(p);
  const auto dt_ns = static_cast<std::int64_t>(dt_s * 1e9);
  gyro.step({Eigen::Vector3d::Zero()}, 0);
  std::vector<double> x;
  x.reserve(static_cast<std::size_t>(samples));
  for (int k = 1; k <= samples; ++k) x.push_back(gyro.step({Eigen::Vector3d::Zero()}, k * dt_ns).w_NB_B_rad_s.x());
  return x;
}

}  // namespace

TEST_CASE("Gyro Allan deviation follows N/sqrt(tau) and K sqrt(tau/3)", "[components][gyro]") {
  // The two slopes of IEEE Std 952-1997 Annex C: angle random walk N gives σ(τ) = N/√τ,
  // rate random walk K gives σ(τ) = K√(τ/3).
  GyroParams arw;
  arw.angle_random_walk_rad_per_sqrt_s = 2.9e-6;
  arw.rate_random_walk_rad_per_s_sqrt_s = 0.0;
  const auto white = stationaryRates(arw, 0.1, 400000);
  for (std::size_t m : {10, 100, 1000}) {
    const double tau = 0.1 * static_cast<double>(m);
    CAPTURE(tau);
    // Relative error of the estimate ~ 1/sqrt(2 (N/m − 1)): < 4 % at τ = 100 s.
    CHECK(allanDeviation(white, 0.1, m) / (arw.angle_random_walk_rad_per_sqrt_s / std::sqrt(tau)) ==
          Approx(1.0).margin(0.08));
  }
  GyroParams rrw;
  rrw.angle_random_walk_rad_per_sqrt_s = 0.0;
  rrw.rate_random_walk_rad_per_s_sqrt_s = 1.0e-9;
  const auto walk = stationaryRates(rrw, 1.0, 1000000);
  for (std::size_t m : {100, 1000}) {
    const double tau = static_cast<double>(m);
    CAPTURE(tau);
    CHECK(allanDeviation(walk, 1.0, m) / (rrw.rate_random_walk_rad_per_s_sqrt_s * std::sqrt(tau / 3.0)) ==
          Approx(1.0).margin(0.15));
  }
}

TEST_CASE("Gyro scale factor and misalignment act on the true rate", "[components][gyro]") {
  GyroParams p;
  p.angle_random_walk_rad_per_sqrt_s = 0.0;
  p.rate_random_walk_rad_per_s_sqrt_s = 0.0;
  p.scale_factor = Eigen::Vector3d(100e-6, -200e-6, 0.0);
  p.misalignment_rad = Eigen::Vector3d(0.0, 0.0, 1e-3);  // triad turned 1 mrad about z
  GyroModel gyro(p);
  const auto out = gyro.step({Eigen::Vector3d(0.1, 0.0, 0.0)}, 0);
  // x reads 0.1 (1 + 100 ppm); the turned y axis sees −sin(1 mrad) of the x rate, scaled.
  CHECK(out.w_NB_B_rad_s.x() == Approx(0.1 * (1 + 100e-6)).epsilon(1e-12));
  CHECK(out.w_NB_B_rad_s.y() == Approx(-0.1 * 1e-3 * (1 - 200e-6)).epsilon(1e-12));
  CHECK(out.w_NB_B_rad_s.z() == 0.0);
  p.scale_factor.x() = 0.2;
  CHECK(p.validate().size() == 1);
}
