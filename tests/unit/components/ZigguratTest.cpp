// SPDX-License-Identifier: Apache-2.0
// The ziggurat (components/common/Ziggurat.hpp) against the normal
// distribution's closed forms: its layers' areas, and the moments, the
// cumulative distribution and the tail of a million draws.
#include <array>
#include <cmath>
#include <cstdint>
#include <random>

#include <catch2/catch.hpp>

#include "components/common/GaussianNoise.hpp"
#include "components/common/Ziggurat.hpp"
#include "tests/unit/components/SampleStats.hpp"

namespace flatsat {
namespace {

// Φ(x), the standard normal distribution function.
double normalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// A count of n draws that is binomial(n, p) lies within 5 of its standard deviations.
bool withinBinomial(int count, double n, double p) {
  return std::abs(count - n * p) < 5.0 * std::sqrt(n * p * (1.0 - p)) + 1.0;
}

}  // namespace

TEST_CASE("Every ziggurat layer has Marsaglia and Tsang's area, the base one with the tail", "[common][noise]") {
  const auto& t = Ziggurat::tables();
  const double v = Ziggurat::kLayerArea;
  const double r = Ziggurat::kTailStart;
  // The base: the rectangle r f(r) plus the tail ∫_r^∞ exp(−x²/2) dx = √(π/2) erfc(r/√2).
  CHECK(r * std::exp(-0.5 * r * r) + std::sqrt(M_PI / 2.0) * std::erfc(r / std::sqrt(2.0)) ==
        Approx(v).epsilon(1e-9));
  for (int i = 1; i < Ziggurat::kLayers; ++i) {
    INFO("layer " << i);
    CHECK(t.x[i] * (t.f[i + 1] - t.f[i]) == Approx(v).epsilon(1e-8));  // the top one closes to 1e-9
    CHECK(t.x[i + 1] < t.x[i]);
  }
  // The layers together cover the half-curve, √(π/2) = 1.2533, and a little more (then rejected).
  CHECK(Ziggurat::kLayers * v > std::sqrt(M_PI / 2.0));
  CHECK(Ziggurat::kLayers * v < 1.01 * std::sqrt(M_PI / 2.0));
}

TEST_CASE("Ziggurat draws follow N(0, 1): moments, distribution function and tails", "[common][noise]") {
  std::mt19937_64 engine(20261127);
  constexpr int kDraws = 1'000'000;
  // Bins of the distribution function from −4 to 4 by 0.5, and the counts beyond the
  // tail start r (where the base layer hands over to the tail method) and beyond 4.5.
  constexpr int kEdges = 17;
  std::array<int, kEdges> below{};
  test::SampleStats stats;
  double sum3 = 0.0, sum4 = 0.0;
  int beyond_r = 0, beyond_4_5 = 0, positive = 0;
  for (int n = 0; n < kDraws; ++n) {
    const double x = Ziggurat::sample(engine);
    stats.add(x);
    sum3 += x * x * x;
    sum4 += x * x * x * x;
    for (int e = 0; e < kEdges; ++e) below[e] += x < -4.0 + 0.5 * e ? 1 : 0;
    beyond_r += std::abs(x) > Ziggurat::kTailStart ? 1 : 0;
    beyond_4_5 += std::abs(x) > 4.5 ? 1 : 0;
    positive += x > 0.0 ? 1 : 0;
  }
  const double n = kDraws;
  // Moments at 5 standard errors: mean and standard deviation (test::checkGaussian), and
  // Var of the sample mean of x³ 15/n, of x⁴ 96/n.
  test::checkGaussian(stats, 0.0, 1.0);
  CHECK(std::abs(sum3 / n) < 5.0 * std::sqrt(15.0 / n));
  CHECK(std::abs(sum4 / n - 3.0) < 5.0 * std::sqrt(96.0 / n));
  // Each count below an edge is binomial(n, Φ(edge)): within 5 of its standard deviations.
  for (int e = 0; e < kEdges; ++e) {
    const double edge = -4.0 + 0.5 * e;
    const double p = normalCdf(edge);
    INFO("x < " << edge);
    CHECK(withinBinomial(below[e], n, p));
  }
  CHECK(withinBinomial(beyond_r, n,
                       std::erfc(Ziggurat::kTailStart / std::sqrt(2.0))));  // 2.58e-4: the tail method's
  CHECK(withinBinomial(beyond_4_5, n, std::erfc(4.5 / std::sqrt(2.0))));    // 6.8e-6
  CHECK(withinBinomial(positive, n, 0.5));                                  // the sign bit
}

TEST_CASE("Gaussian noise replays its draws after reset and scales them by sigma", "[common][noise]") {
  GaussianNoise noise(7);
  const Eigen::Vector3d first = noise.vector<3>(2.0);
  noise.sample(1.0);
  noise.reset();
  CHECK(noise.vector<3>(2.0) == first);
  std::mt19937_64 engine(7);
  CHECK(first.x() == 2.0 * Ziggurat::sample(engine));
}

}  // namespace flatsat
