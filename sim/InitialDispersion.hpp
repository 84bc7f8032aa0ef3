// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace flatsat::sim {

/// A tumble drawn from a seed: attitude uniform over SO(3), rate of a given
/// size about an axis uniform over the sphere. The draws use splitmix64
/// (Steele, Lea & Flood, "Fast splittable pseudorandom number generators",
/// OOPSLA 2014) and closed-form maps, not <random>'s distributions, so a seed
/// gives the same tumble with every standard library: `flatsat run --seed N`
/// and `flatsat study` case N start from the same state.
struct Tumble {
  Eigen::Quaterniond q_NB = Eigen::Quaterniond::Identity();  // body → inertial
  Eigen::Vector3d w_NB_B_rad_s = Eigen::Vector3d::Zero();    // [rad/s]
};

/// rate_rad_s [rad/s] ≥ 0: the size of the body rate.
Tumble dispersedTumble(std::uint64_t seed, double rate_rad_s);

}  // namespace flatsat::sim
