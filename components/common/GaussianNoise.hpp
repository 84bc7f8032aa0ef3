// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <random>

#include <Eigen/Core>

namespace flatsat {

/// Seeded zero-mean Gaussian source shared by the sensor models.
///
/// reset() restores the engine *and* the distribution: std::normal_distribution
/// caches the second value of each Box–Muller/Marsaglia pair, so reseeding the
/// engine alone would not replay the same sequence.
class GaussianNoise {
 public:
  explicit GaussianNoise(std::uint64_t seed) : seed_(seed), engine_(seed) {}

  void reset() {
    engine_.seed(seed_);
    normal_.reset();
  }

  /// One draw with standard deviation sigma.
  double sample(double sigma) { return sigma * normal_(engine_); }

  /// N independent draws with standard deviation sigma.
  template <int N>
  Eigen::Matrix<double, N, 1> vector(double sigma) {
    Eigen::Matrix<double, N, 1> v;
    for (int i = 0; i < N; ++i) {
      v[i] = sample(sigma);
    }
    return v;
  }

 private:
  std::uint64_t seed_;
  std::mt19937_64 engine_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace flatsat
