// SPDX-License-Identifier: Apache-2.0
#include "sim/Teme.hpp"

#include <cmath>

#include "sim/Time.hpp"

namespace flatsat::sim {

Eigen::Matrix3d R_ET(double jd_ut1) {
  const double theta = gmst_rad(jd_ut1);
  const double c = std::cos(theta);
  const double s = std::sin(theta);
  Eigen::Matrix3d r;
  r << c, s, 0.0,  //
      -s, c, 0.0,  //
      0.0, 0.0, 1.0;
  return r;
}

Eigen::Matrix3d R_NT(double jd_ut1) { return R_EN(jd_ut1).transpose() * R_ET(jd_ut1); }

}  // namespace flatsat::sim
