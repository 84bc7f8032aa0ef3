// SPDX-License-Identifier: Apache-2.0
#include "sim/Teme.hpp"

#include <cmath>

#include "sim/Attitude.hpp"
#include "sim/Time.hpp"

namespace flatsat::sim {

Eigen::Matrix3d R_ET(double jd_ut1) { return rot3(gmst_rad(jd_ut1)); }

Eigen::Matrix3d R_NT(double jd_ut1) { return R_EN(jd_ut1).transpose() * R_ET(jd_ut1); }

}  // namespace flatsat::sim
