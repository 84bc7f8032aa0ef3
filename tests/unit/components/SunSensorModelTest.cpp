// SPDX-License-Identifier: Apache-2.0
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <catch2/catch.hpp>

#include "components/sun_sensor/SunSensorModel.hpp"
#include "tests/support/TestUnits.hpp"
#include "tests/unit/components/SampleStats.hpp"

using flatsat::sun_sensor::SunSensorModel;
using flatsat::sun_sensor::SunSensorParams;
using flatsat::test::checkGaussian;
using flatsat::test::SampleStats;

namespace {

/// Unit vector at angle `off` from +x, in the plane spanned by +x and `dir`.
Eigen::Vector3d offBoresight(double off, const Eigen::Vector3d& dir) {
  return std::cos(off) * Eigen::Vector3d::UnitX() + std::sin(off) * dir.normalized();
}

SunSensorParams noiseFree() {
  SunSensorParams p;
  p.noise_rad = 0.0;
  return p;
}

}  // namespace

TEST_CASE("Sun sensor reports the Sun inside its field of view", "[components][sun_sensor]") {
  GIVEN("a noise-free sensor with a 60° half-angle") {
    SunSensorModel sensor(noiseFree());
    WHEN("the Sun is 30° off the boresight") {
      const Eigen::Vector3d sun = offBoresight(30.0 * kDeg, Eigen::Vector3d(0.0, 1.0, -2.0));
      const auto out = sensor.step({sun, 1.0}, 0);
      THEN("it is valid and exact") {
        CHECK(out.valid);
        CHECK((out.sun_B_unit - sun).norm() < 1e-14);
      }
    }
    WHEN("the Sun is just inside and just outside the cone") {
      const Eigen::Vector3d dir(0.0, -1.0, 1.0);
      THEN("only the inside one is valid; the other reads zero") {
        CHECK(sensor.step({offBoresight(59.9 * kDeg, dir), 1.0}, 0).valid);
        const auto out = sensor.step({offBoresight(60.1 * kDeg, dir), 1.0}, 0);
        CHECK_FALSE(out.valid);
        CHECK(out.sun_B_unit == Eigen::Vector3d::Zero());
      }
    }
    WHEN("the Sun is behind the sensor") {
      THEN("it is invalid") { CHECK_FALSE(sensor.step({-Eigen::Vector3d::UnitX(), 1.0}, 0).valid); }
    }
  }
}

TEST_CASE("Sun sensor sees no Sun below the illumination threshold", "[components][sun_sensor]") {
  SunSensorModel sensor(noiseFree());  // min_illumination = 0.5
  const Eigen::Vector3d sun = Eigen::Vector3d::UnitX();
  CHECK_FALSE(sensor.step({sun, 0.0}, 0).valid);  // umbra
  const auto penumbra = sensor.step({sun, 0.49}, 0);
  CHECK_FALSE(penumbra.valid);
  CHECK(penumbra.sun_B_unit == Eigen::Vector3d::Zero());
  CHECK(sensor.step({sun, 0.5}, 0).valid);
}

TEST_CASE("Sun sensor honours a boresight other than +x", "[components][sun_sensor]") {
  SunSensorParams p = noiseFree();
  p.boresight_B = -Eigen::Vector3d::UnitZ();
  SunSensorModel sensor(p);
  const Eigen::Vector3d sun = Eigen::Vector3d(0.3, 0.2, -1.0).normalized();
  const auto out = sensor.step({sun, 1.0}, 0);
  CHECK(out.valid);
  CHECK((out.sun_B_unit - sun).norm() < 1e-14);
  CHECK_FALSE(sensor.step({Eigen::Vector3d::UnitX(), 1.0}, 0).valid);  // 90° off −z
}

TEST_CASE("Sun sensor on a mounting known wrongly turns every reading by the error", "[components][sun_sensor]") {
  // Mounted on +x, believed 2 deg towards +y: flight software converts the two
  // angles on the believed axes, so every direction turns by 2 deg about z.
  SunSensorParams p = noiseFree();
  const double error_rad = 2.0 * kDeg;
  p.boresight_onboard_B = Eigen::Vector3d(std::cos(error_rad), std::sin(error_rad), 0.0);
  SunSensorModel sensor(p);
  const Eigen::AngleAxisd believed(error_rad, Eigen::Vector3d::UnitZ());
  for (const Eigen::Vector3d& sun : {Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Vector3d(0.9, 0.3, -0.2).normalized(),
                                     offBoresight(40.0 * kDeg, Eigen::Vector3d(0.0, -1.0, 1.0))}) {
    const auto out = sensor.step({sun, 1.0}, 0);
    REQUIRE(out.valid);
    CHECK((out.sun_B_unit - believed * sun).norm() < 1e-14);
    CHECK(std::acos(std::clamp(out.sun_B_unit.dot(sun), -1.0, 1.0)) <= error_rad + 1e-12);
  }
  // The field of view is the true mounting's: 59 deg off +x is seen, 61 deg is not.
  CHECK(sensor.step({offBoresight(59.0 * kDeg, Eigen::Vector3d::UnitZ()), 1.0}, 0).valid);
  CHECK_FALSE(sensor.step({offBoresight(61.0 * kDeg, Eigen::Vector3d::UnitZ()), 1.0}, 0).valid);
}

TEST_CASE("Sun sensor angle noise has the set sigma on each axis", "[components][sun_sensor]") {
  SunSensorParams p;
  p.noise_rad = 1e-3;
  SunSensorModel sensor(p);
  // Boresight +x, transverse angles measured towards y and z: α = atan2(s_y, s_x), β = atan2(s_z, s_x).
  const double alpha0 = 10.0 * kDeg;
  const double beta0 = -5.0 * kDeg;
  const Eigen::Vector3d sun = Eigen::Vector3d(1.0, std::tan(alpha0), std::tan(beta0)).normalized();
  SampleStats alpha;
  SampleStats beta;
  for (int k = 0; k < 20000; ++k) {
    const auto out = sensor.step({sun, 1.0}, k);
    REQUIRE(out.valid);
    REQUIRE(std::abs(out.sun_B_unit.norm() - 1.0) < 1e-14);
    alpha.add(std::atan2(out.sun_B_unit.y(), out.sun_B_unit.x()));
    beta.add(std::atan2(out.sun_B_unit.z(), out.sun_B_unit.x()));
  }
  checkGaussian(alpha, alpha0, p.noise_rad);
  checkGaussian(beta, beta0, p.noise_rad);
}

TEST_CASE("Sun sensor noise replays from the seed, eclipses included", "[components][sun_sensor]") {
  SunSensorParams p;
  p.noise_rad = 1e-3;
  SunSensorModel lit(p);
  SunSensorModel eclipsed(p);
  const Eigen::Vector3d sun = offBoresight(20.0 * kDeg, Eigen::Vector3d::UnitY());
  Eigen::Vector3d first[12];
  for (int k = 0; k < 12; ++k) {
    first[k] = lit.step({sun, 1.0}, k).sun_B_unit;
    // Samples 4..7 in umbra must not shift the noise of the samples after them.
    const auto out = eclipsed.step({sun, (k >= 4 && k < 8) ? 0.0 : 1.0}, k);
    if (k < 4 || k >= 8) {
      CHECK(out.sun_B_unit == first[k]);
    }
  }
  lit.reset();
  for (int k = 0; k < 12; ++k) {
    CHECK(lit.step({sun, 1.0}, k).sun_B_unit == first[k]);
  }
}

TEST_CASE("Sun sensor never reports an angle beyond its field of view", "[components][sun_sensor]") {
  SunSensorParams p;
  p.noise_rad = 0.5;  // absurd noise near the edge drives the raw angles past the cone
  SunSensorModel sensor(p);
  const Eigen::Vector3d sun = offBoresight(55.0 * kDeg, Eigen::Vector3d::UnitY());
  for (int k = 0; k < 2000; ++k) {
    const auto out = sensor.step({sun, 1.0}, k);
    REQUIRE(out.sun_B_unit.allFinite());
    CHECK(std::abs(out.sun_B_unit.norm() - 1.0) < 1e-14);
    CHECK(std::abs(std::atan2(out.sun_B_unit.y(), out.sun_B_unit.x())) <= p.fov_half_angle_rad + 1e-12);
    CHECK(std::abs(std::atan2(out.sun_B_unit.z(), out.sun_B_unit.x())) <= p.fov_half_angle_rad + 1e-12);
  }
}

TEST_CASE("Sun sensor params reject bad values", "[components][sun_sensor]") {
  CHECK(SunSensorParams{}.validate().empty());
  SunSensorParams p;
  p.boresight_B = Eigen::Vector3d(1.0, 1.0, 0.0);
  p.noise_rad = -1e-3;
  p.fov_half_angle_rad = std::numbers::pi / 2.0;
  p.min_illumination = 1.5;
  const auto errors = p.validate();
  REQUIRE(errors.size() == 4);
  CHECK(errors[0].rfind("boresight_B:", 0) == 0);
  CHECK(errors[1].rfind("noise_rad:", 0) == 0);
  CHECK(errors[2].rfind("fov_half_angle_rad:", 0) == 0);
  CHECK(errors[3].rfind("min_illumination:", 0) == 0);
  CHECK_THROWS_AS(SunSensorModel(p), std::invalid_argument);
}
