// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/Constants.hpp"
#include "sim/Geodetic.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

namespace {

const double kA = kEarthEquatorialRadius_m;
const double kB = kA * (1.0 - kEarthFlattening);
const double kE2 = kEarthFlattening * (2.0 - kEarthFlattening);

// Unit outward normal of the ellipsoid x²/a² + y²/a² + z²/b² = 1 at a surface point:
// the direction of its gradient (the definition of geodetic latitude, independent of
// the prime-vertical radius used by earthFixedFromGeodetic).
Eigen::Vector3d ellipsoidNormal(const Eigen::Vector3d& surface) {
  return Eigen::Vector3d(surface.x() / (kA * kA), surface.y() / (kA * kA), surface.z() / (kB * kB)).normalized();
}

}  // namespace

TEST_CASE("earthFixedFromGeodetic places points on and along the ellipsoid normal", "[sim][geomag]") {
  GIVEN("points on the equator and at the poles") {
    CHECK((earthFixedFromGeodetic({0.0, 0.0, 0.0}) - Eigen::Vector3d(kA, 0.0, 0.0)).norm() < 1e-9);
    CHECK((earthFixedFromGeodetic({0.0, 0.5 * std::numbers::pi, 1000.0}) - Eigen::Vector3d(0.0, kA + 1000.0, 0.0))
              .norm() < 1e-9);
    CHECK((earthFixedFromGeodetic({90.0 * kDeg, 0.3, 0.0}) - Eigen::Vector3d(0.0, 0.0, kB)).norm() < 1e-6);
    CHECK((earthFixedFromGeodetic({-90.0 * kDeg, 0.0, 500e3}) - Eigen::Vector3d(0.0, 0.0, -kB - 500e3)).norm() < 1e-6);
  }
  GIVEN("any latitude at zero height") {
    for (double lat = -89.0; lat <= 89.0; lat += 7.0) {
      const GeodeticPosition p{lat * kDeg, 0.7, 0.0};
      const Eigen::Vector3d r = earthFixedFromGeodetic(p);
      THEN("the point lies on the ellipsoid, its normal at the geodetic latitude") {
        CHECK(r.x() * r.x() / (kA * kA) + r.y() * r.y() / (kA * kA) + r.z() * r.z() / (kB * kB) ==
              Approx(1.0).epsilon(1e-14));
        const Eigen::Vector3d up = ellipsoidNormal(r);
        CHECK(std::asin(up.z()) == Approx(p.latitude_rad).margin(1e-14));
        CHECK(std::atan2(up.y(), up.x()) == Approx(0.7).margin(1e-14));
        AND_THEN("height moves the point along that normal") {
          const Eigen::Vector3d high = earthFixedFromGeodetic({p.latitude_rad, 0.7, 700e3});
          CHECK((high - (r + 700e3 * up)).norm() < 1e-8);
        }
      }
    }
  }
}

TEST_CASE("geodeticFromEarthFixed inverts to better than a millimetre", "[sim][geomag]") {
  GIVEN("points on the axes") {
    const GeodeticPosition north = geodeticFromEarthFixed({0.0, 0.0, 7e6});
    CHECK(north.latitude_rad == Approx(0.5 * std::numbers::pi).margin(1e-15));
    CHECK(north.longitude_rad == 0.0);
    CHECK(north.height_m == Approx(7e6 - kB).margin(1e-6));
    const GeodeticPosition south = geodeticFromEarthFixed({0.0, 0.0, -6.3e6});
    CHECK(south.latitude_rad == Approx(-0.5 * std::numbers::pi).margin(1e-15));
    CHECK(south.height_m == Approx(6.3e6 - kB).margin(1e-6));
    const GeodeticPosition equator = geodeticFromEarthFixed({-7e6, 0.0, 0.0});
    CHECK(equator.latitude_rad == Approx(0.0).margin(1e-15));
    CHECK(std::abs(equator.longitude_rad) == Approx(std::numbers::pi).margin(1e-15));
    CHECK(equator.height_m == Approx(7e6 - kA).margin(1e-6));
  }
  GIVEN("a grid of latitudes (poles included), longitudes and heights from −1 to 1000 km") {
    double worst_position_m = 0.0;
    double worst_height_m = 0.0;
    double worst_latitude_rad = 0.0;
    for (double lat : {-90.0, -89.9999999, -89.99, -75.0, -45.0, -12.5, 0.0, 1e-9, 30.0, 60.0, 89.999, 90.0}) {
      for (double lon : {-180.0, -97.3, 0.0, 45.0, 179.99}) {
        for (double h : {-1e3, 0.0, 1.0, 400e3, 600e3, 1000e3}) {
          const GeodeticPosition p{lat * kDeg, lon * kDeg, h};
          const Eigen::Vector3d r = earthFixedFromGeodetic(p);
          const GeodeticPosition q = geodeticFromEarthFixed(r);
          worst_position_m = std::max(worst_position_m, (earthFixedFromGeodetic(q) - r).norm());
          worst_height_m = std::max(worst_height_m, std::abs(q.height_m - h));
          worst_latitude_rad = std::max(worst_latitude_rad, std::abs(q.latitude_rad - p.latitude_rad));
          if (std::abs(lat) < 90.0) CHECK(std::cos(q.longitude_rad - p.longitude_rad) == Approx(1.0));
        }
      }
    }
    THEN("position, height and latitude come back to well under a millimetre") {
      CHECK(worst_position_m < 1e-6);
      CHECK(worst_height_m < 1e-6);
      CHECK(worst_latitude_rad * kA < 1e-6);
    }
  }
}

TEST_CASE("geocentric coordinates of geodetic points", "[sim][geomag]") {
  GIVEN("the equator and the poles, where both latitudes agree") {
    const GeocentricPosition eq = geocentricFromGeodetic({0.0, 1.2, 300e3});
    CHECK(eq.radius_m == Approx(kA + 300e3).epsilon(1e-15));
    CHECK(eq.latitude_rad == Approx(0.0).margin(1e-15));
    CHECK(eq.longitude_rad == 1.2);
    const GeocentricPosition pole = geocentricFromGeodetic({-0.5 * std::numbers::pi, 1.2, 300e3});
    CHECK(pole.radius_m == Approx(kB + 300e3).epsilon(1e-15));
    CHECK(pole.latitude_rad == Approx(-0.5 * std::numbers::pi).margin(1e-12));
    CHECK(pole.longitude_rad == 1.2);  // kept, so that the NED frames stay defined
  }
  GIVEN("a point on the surface") {
    for (double lat : {-60.0, -10.0, 33.3, 45.0, 80.0}) {
      const GeocentricPosition c = geocentricFromGeodetic({lat * kDeg, 0.0, 0.0});
      THEN("tan φ′ = (1 − e²) tan φ, the classical surface relation") {
        CHECK(std::tan(c.latitude_rad) == Approx((1.0 - kE2) * std::tan(lat * kDeg)).epsilon(1e-13));
      }
    }
    THEN("the largest difference φ − φ′, at 45°, is the textbook 11.5′") {
      const double d = 45.0 * kDeg - geocentricFromGeodetic({45.0 * kDeg, 0.0, 0.0}).latitude_rad;
      CHECK(d / kDeg * 60.0 == Approx(11.5).margin(0.1));
    }
  }
  GIVEN("an Earth-fixed position") {
    const Eigen::Vector3d r(-3.1e6, 4.2e6, -4.4e6);
    const GeocentricPosition c = geocentricFromEarthFixed(r);
    CHECK(c.radius_m == Approx(r.norm()).epsilon(1e-15));
    const Eigen::Vector3d back =
        c.radius_m * Eigen::Vector3d(std::cos(c.latitude_rad) * std::cos(c.longitude_rad),
                                     std::cos(c.latitude_rad) * std::sin(c.longitude_rad), std::sin(c.latitude_rad));
    CHECK((back - r).norm() < 1e-8);
  }
}

TEST_CASE("NED rotations", "[sim][geomag]") {
  GIVEN("the geodetic NED frame at latitude 0, longitude 0") {
    const Eigen::Matrix3d R = R_EG({0.0, 0.0, 0.0});
    THEN("north is +z, east +y, down −x") {
      CHECK((R.col(0) - Eigen::Vector3d::UnitZ()).norm() < 1e-15);
      CHECK((R.col(1) - Eigen::Vector3d::UnitY()).norm() < 1e-15);
      CHECK((R.col(2) + Eigen::Vector3d::UnitX()).norm() < 1e-15);
    }
  }
  GIVEN("the north pole seen from longitude λ") {
    const double lon = 0.8;
    const Eigen::Matrix3d R = R_EG({0.5 * std::numbers::pi, lon, 0.0});
    THEN("down is −z and north points along the meridian λ + 180°") {
      CHECK((R.col(2) + Eigen::Vector3d::UnitZ()).norm() < 1e-15);
      CHECK((R.col(0) + Eigen::Vector3d(std::cos(lon), std::sin(lon), 0.0)).norm() < 1e-15);
    }
  }
  GIVEN("any point") {
    const GeodeticPosition p{52.0 * kDeg, -3.0 * kDeg, 800e3};
    const GeocentricPosition c = geocentricFromGeodetic(p);
    const Eigen::Matrix3d R = R_EG(p);
    THEN("R_EG is a rotation whose down axis is the inward ellipsoid normal") {
      CHECK((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-15);
      CHECK(R.determinant() == Approx(1.0));
      CHECK((R.col(2) + ellipsoidNormal(earthFixedFromGeodetic({p.latitude_rad, p.longitude_rad, 0.0}))).norm() <
            1e-12);
    }
    THEN("R_EC points down at the centre and R_EG R_GC = R_EC") {
      const Eigen::Matrix3d R_EC_ = R_EC(c);
      CHECK((R_EC_.col(2) + earthFixedFromGeodetic(p).normalized()).norm() < 1e-12);
      CHECK((R * R_GC(p.latitude_rad, c.latitude_rad) - R_EC_).norm() < 1e-15);
    }
  }
}
