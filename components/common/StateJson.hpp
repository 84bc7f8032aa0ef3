// SPDX-License-Identifier: Apache-2.0
#pragma once
// Eigen values in a component's checkpoint (bus/Checkpoint.hpp): matrices as
// row-major arrays of numbers, quaternions as [w, x, y, z] (Hamilton, scalar
// first, as on the bus).
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

namespace flatsat::state_json {

template <class Derived>
nlohmann::json matrix(const Eigen::MatrixBase<Derived>& m) {
  auto array = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) array.push_back(m(r, c));
  }
  return array;
}

/// Fills the fixed-size `m` from j[key]; throws std::invalid_argument naming
/// the key when it is not an array of exactly as many finite numbers.
template <class Matrix>
void read(const nlohmann::json& j, const std::string& key, Matrix& m) {
  const auto& array = j.at(key);
  if (!array.is_array() || array.size() != static_cast<std::size_t>(m.size())) {
    throw std::invalid_argument(key + ": expected " + std::to_string(m.size()) + " numbers");
  }
  std::size_t i = 0;
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) {
      const double v = array[i++].get<double>();
      if (!std::isfinite(v)) throw std::invalid_argument(key + ": not finite");
      m(r, c) = v;
    }
  }
}

inline nlohmann::json quaternion(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }

inline Eigen::Quaterniond readQuaternion(const nlohmann::json& j, const std::string& key) {
  Eigen::Vector4d wxyz;
  read(j, key, wxyz);
  if (std::abs(wxyz.norm() - 1.0) > 1e-9) throw std::invalid_argument(key + ": not a unit quaternion");
  return Eigen::Quaterniond(wxyz(0), wxyz(1), wxyz(2), wxyz(3));
}

}  // namespace flatsat::state_json
