// SPDX-License-Identifier: Apache-2.0
#include "sim/InitialDispersion.hpp"

#include <cmath>

#include "sim/Constants.hpp"

namespace flatsat::sim {

namespace {

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_;
};

}  // namespace

Tumble dispersedTumble(std::uint64_t seed, double rate_rad_s) {
  SplitMix64 draw(seed);
  // Shoemake, "Uniform random rotations", Graphics Gems III (1992): three
  // uniforms to a unit quaternion uniform over SO(3).
  const double u1 = draw.uniform(), u2 = kTwoPi * draw.uniform(), u3 = kTwoPi * draw.uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  Tumble tumble;
  tumble.q_NB = Eigen::Quaterniond(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
  // Archimedes: z uniform in [−1, 1] and a uniform azimuth give a uniform direction.
  const double z = 2.0 * draw.uniform() - 1.0, phi = kTwoPi * draw.uniform();
  const double r = std::sqrt(1.0 - z * z);
  tumble.w_NB_B_rad_s = rate_rad_s * Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), z);
  return tumble;
}

}  // namespace flatsat::sim
