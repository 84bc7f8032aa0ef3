// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <random>

#include <Eigen/Core>

#include "components/common/Ziggurat.hpp"

namespace flatsat {

/// Seeded zero-mean Gaussian source shared by the sensor models. The draws
/// follow from the seed and the ziggurat below, not from which standard
/// library's normal_distribution (an unspecified algorithm) is linked.
class GaussianNoise {
 public:
  explicit GaussianNoise(std::uint64_t seed) : seed_(seed), engine_(seed) {}

  /// Replays the sequence from its first draw.
  void reset() { engine_.seed(seed_); }

  /// One draw with standard deviation sigma.
  double sample(double sigma) { return sigma * Ziggurat::sample(engine_); }

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
};

}  // namespace flatsat
