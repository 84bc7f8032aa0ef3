// SPDX-License-Identifier: Apache-2.0
#include "components/common/WheelGeometry.hpp"

#include <algorithm>

#include "components/common/Validation.hpp"

namespace flatsat {

namespace {
// validate() rejects a count outside 1..kMaxWheels, but the algorithms' step() must not read
// out of bounds even so.
int liveCount(int count) { return std::clamp(count, 0, WheelGeometry::kMaxWheels); }
}  // namespace

std::vector<std::string> WheelGeometry::validate(const std::string& prefix) const {
  const std::string p = prefix.empty() ? std::string() : prefix + ".";
  std::vector<std::string> errors;
  requireInRange(errors, p + "count", count, 1, kMaxWheels);
  if (!errors.empty()) {
    return errors;  // the per-wheel checks need a valid count
  }
  for (int i = 0; i < count; ++i) {
    const std::string n = std::to_string(i);
    require(errors, isUnit(axes_B.col(i)), p + "axes_B", "column " + n + " must be a unit vector");
    require(errors, isPositive(inertia_kg_m2[i]), p + "inertia_kg_m2",
            "wheel " + n + " must be finite and > 0");
  }
  return errors;
}

Eigen::Vector3d WheelGeometry::momentum_B_Nms(const Eigen::Vector4d& wheel_speed_rad_s) const {
  const int n = liveCount(count);
  return axes_B.leftCols(n) * inertia_kg_m2.head(n).cwiseProduct(wheel_speed_rad_s.head(n));
}

Eigen::Matrix<double, 3, WheelGeometry::kMaxWheels> WheelGeometry::liveAxes_B() const {
  const int n = liveCount(count);
  Eigen::Matrix<double, 3, kMaxWheels> live = Eigen::Matrix<double, 3, kMaxWheels>::Zero();
  live.leftCols(n) = axes_B.leftCols(n);
  return live;
}

}  // namespace flatsat
