// SPDX-License-Identifier: Apache-2.0
// Shared by the component tests: sample statistics and the bounds a Gaussian sample must meet.
#pragma once

#include <cmath>
#include <cstddef>

#include <catch2/catch.hpp>

namespace flatsat::test {

/// Running mean and variance (Welford 1962, Technometrics 4(3)): no cancellation over many samples.
class SampleStats {
 public:
  void add(double x) {
    ++n_;
    const double d = x - mean_;
    mean_ += d / static_cast<double>(n_);
    m2_ += d * (x - mean_);
  }
  std::size_t count() const { return n_; }
  double mean() const { return mean_; }
  double stddev() const { return std::sqrt(m2_ / static_cast<double>(n_ - 1)); }

 private:
  std::size_t n_ = 0;
  double mean_ = 0.0;
  double m2_ = 0.0;
};

/// The sample is consistent with N(mu, sigma²) at 5σ of its estimators: the standard error of
/// the mean is σ/√n, that of the sample standard deviation ≈ σ/√(2n).
inline void checkGaussian(const SampleStats& s, double mu, double sigma) {
  const double n = static_cast<double>(s.count());
  CHECK(std::abs(s.mean() - mu) < 5.0 * sigma / std::sqrt(n));
  CHECK(std::abs(s.stddev() / sigma - 1.0) < 5.0 / std::sqrt(2.0 * n));
}

}  // namespace flatsat::test
