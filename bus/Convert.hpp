// SPDX-License-Identifier: Apache-2.0
#pragma once
// IDL fixed arrays <-> Eigen, for the nodes' two mapping functions.
#include <array>
#include <cstddef>

#include <Eigen/Dense>

namespace flatsat::bus {

template <std::size_t N, class Vector>
void put(std::array<double, N>& out, const Vector& v) {
  static_assert(Vector::SizeAtCompileTime == static_cast<int>(N), "size mismatch");
  for (std::size_t i = 0; i < N; ++i) out[i] = v[static_cast<Eigen::Index>(i)];
}

/// Hamilton, scalar first on the wire.
inline void put(std::array<double, 4>& out, const Eigen::Quaterniond& q) {
  out = {q.w(), q.x(), q.y(), q.z()};
}

inline Eigen::Vector3d vec3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
inline Eigen::Vector4d vec4(const std::array<double, 4>& a) { return {a[0], a[1], a[2], a[3]}; }
inline Eigen::Quaterniond quat(const std::array<double, 4>& a) {
  return Eigen::Quaterniond(a[0], a[1], a[2], a[3]);
}

}  // namespace flatsat::bus
