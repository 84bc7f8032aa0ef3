// SPDX-License-Identifier: Apache-2.0
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/Teme.hpp"
#include "sim/Time.hpp"

using namespace flatsat::sim;

SCENARIO("TEME rotates to the pseudo-Earth-fixed frame by GMST", "[sim][sgp4][teme]") {
  GIVEN("the TEME example of Vallado et al. 2006: 2004-04-06 07:51:28.386009 UTC, UT1 - UTC = -0.4399619 s") {
    const double jd_ut1 = julianDate(UtcEpoch{2004, 4, 6, 7, 51, 28.386009 - 0.4399619});
    const Eigen::Vector3d r_T_km(5094.18016210, 6127.64465950, 6380.34453270);
    WHEN("the position is rotated with R_ET") {
      const Eigen::Vector3d r_E_km = R_ET(jd_ut1) * r_T_km;
      THEN("it is the published PEF position to its 1e-7 km") {
        CHECK(r_E_km.x() == Approx(-1033.4750313).margin(1e-7));
        CHECK(r_E_km.y() == Approx(7901.3055856).margin(1e-7));
        CHECK(r_E_km.z() == Approx(6380.3445327).margin(1e-7));
      }
    }
  }
  GIVEN("any date") {
    const double jd = 2460000.25;
    THEN("R_ET is a proper rotation about z that takes the GMST direction to x") {
      const Eigen::Matrix3d r = R_ET(jd);
      CHECK((r * r.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-15);
      CHECK(r.determinant() == Approx(1.0).margin(1e-15));
      const double theta = gmst_rad(jd);
      CHECK((r * Eigen::Vector3d(std::cos(theta), std::sin(theta), 0.0) - Eigen::Vector3d::UnitX()).norm() < 1e-15);
      CHECK(r * Eigen::Vector3d::UnitZ() == Eigen::Vector3d::UnitZ());
    }
  }
}

TEST_CASE("R_NT: the rig's inertial frame, defined by R_EN = Rz(GMST), coincides with TEME", "[sim][sgp4][teme]") {
  for (const double jd : {2451545.0, 2453101.827411, 2460676.5, 2470000.9}) {
    CHECK((R_NT(jd) - Eigen::Matrix3d::Identity()).norm() < 1e-15);
    CHECK((R_EN(jd) * R_NT(jd) - R_ET(jd)).norm() < 1e-15);
  }
}
