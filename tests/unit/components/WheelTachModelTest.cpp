// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <limits>
#include <stdexcept>

#include <catch2/catch.hpp>

#include "components/wheel_tach/WheelTachModel.hpp"
#include "tests/unit/components/SampleStats.hpp"

using flatsat::test::checkGaussian;
using flatsat::test::SampleStats;
using flatsat::wheel_tach::WheelTachModel;
using flatsat::wheel_tach::WheelTachParams;

namespace {

const Eigen::Vector4d kSpeeds_rad_s(150.0, -320.5, 12.25, 999.0);

}  // namespace

TEST_CASE("Wheel tach reads the active wheels and zeroes the rest", "[components][wheel_tach]") {
  GIVEN("three noise-free tachometers and a speed in the unused fourth slot") {
    WheelTachParams p;
    p.wheel_count = 3;
    p.noise_rad_s = 0.0;
    WheelTachModel tach(p);
    const auto out = tach.step({kSpeeds_rad_s}, 0);
    THEN("the active speeds pass, slot 3 is zero") {
      CHECK(out.wheel_speed_rad_s == Eigen::Vector4d(150.0, -320.5, 12.25, 0.0));
    }
  }
}

TEST_CASE("Wheel tach noise has the set sigma on every wheel", "[components][wheel_tach]") {
  WheelTachParams p;
  p.wheel_count = 4;
  p.noise_rad_s = 0.05;
  WheelTachModel tach(p);
  SampleStats stats[4];
  for (int k = 0; k < 20000; ++k) {
    const auto out = tach.step({kSpeeds_rad_s}, k);
    for (int i = 0; i < 4; ++i) {
      stats[i].add(out.wheel_speed_rad_s[i]);
    }
  }
  for (int i = 0; i < 4; ++i) {
    checkGaussian(stats[i], kSpeeds_rad_s[i], p.noise_rad_s);
  }
}

TEST_CASE("Wheel tach quantises to its resolution", "[components][wheel_tach]") {
  WheelTachParams p;
  p.wheel_count = 4;
  p.noise_rad_s = 0.0;
  p.quantum_rad_s = 0.1;
  WheelTachModel tach(p);
  const auto out = tach.step({Eigen::Vector4d(1.04, -2.06, 0.149, 7.0)}, 0);
  CHECK((out.wheel_speed_rad_s - Eigen::Vector4d(1.0, -2.1, 0.1, 7.0)).norm() < 1e-12);
}

TEST_CASE("Wheel tach noise replays from the seed", "[components][wheel_tach]") {
  WheelTachParams p;
  p.wheel_count = 4;
  WheelTachModel a(p);
  WheelTachModel b(p);
  p.seed += 1;
  WheelTachModel other(p);
  Eigen::Vector4d first[10];
  bool differs = false;
  for (int k = 0; k < 10; ++k) {
    first[k] = a.step({kSpeeds_rad_s}, k).wheel_speed_rad_s;
    CHECK(b.step({kSpeeds_rad_s}, k).wheel_speed_rad_s == first[k]);
    differs = differs || other.step({kSpeeds_rad_s}, k).wheel_speed_rad_s != first[k];
  }
  CHECK(differs);
  a.reset();
  for (int k = 0; k < 10; ++k) {
    CHECK(a.step({kSpeeds_rad_s}, k).wheel_speed_rad_s == first[k]);
  }
}

TEST_CASE("Wheel tach params reject bad values", "[components][wheel_tach]") {
  CHECK(WheelTachParams{}.validate().empty());
  WheelTachParams p;
  p.noise_rad_s = -0.1;
  p.quantum_rad_s = std::numeric_limits<double>::quiet_NaN();
  for (int count : {0, 5}) {
    p.wheel_count = count;
    const auto errors = p.validate();
    REQUIRE(errors.size() == 3);
    CHECK(errors[0].rfind("wheel_count:", 0) == 0);
    CHECK(errors[1].rfind("noise_rad_s:", 0) == 0);
    CHECK(errors[2].rfind("quantum_rad_s:", 0) == 0);
    CHECK_THROWS_AS(WheelTachModel(p), std::invalid_argument);
  }
}
