// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "components/common/Validation.hpp"
#include "components/common/WheelGeometry.hpp"

using flatsat::WheelGeometry;

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

TEST_CASE("Wheel geometry sums the momentum of the live wheels only", "[common][components][wheel_geometry]") {
  GIVEN("two live wheels on x and a skewed axis, garbage in the unused slots") {
    const double s = 1.0 / std::sqrt(2.0);
    WheelGeometry g;
    g.count = 2;
    g.axes_B << 1.0, 0.0, 5.0, kNaN,  //
        0.0, s, 5.0, kNaN,            //
        0.0, s, 5.0, kNaN;
    g.inertia_kg_m2 = Eigen::Vector4d(2e-4, 4e-4, 1.0, kNaN);
    WHEN("the wheels spin at 100 and -50 rad/s") {
      const Eigen::Vector3d h = g.momentum_B_Nms(Eigen::Vector4d(100.0, -50.0, 1e6, kNaN));
      THEN("h = Σ a_i I_i Ω_i = 0.02·x − 0.02·(0, s, s)") {
        CHECK((h - Eigen::Vector3d(0.02, -0.02 * s, -0.02 * s)).norm() < 1e-17);
      }
    }
    THEN("the live axes keep columns 0 and 1 and zero the rest") {
      const Eigen::Matrix<double, 3, 4> A = g.liveAxes_B();
      CHECK(A.leftCols(2) == g.axes_B.leftCols(2));
      CHECK(A.rightCols(2) == Eigen::Matrix<double, 3, 2>::Zero());
    }
    THEN("only the live slots are validated") { CHECK(g.validate("wheels").empty()); }
  }
}

TEST_CASE("Wheel geometry reports every violation under its prefix", "[common][components][wheel_geometry]") {
  WheelGeometry g;
  CHECK(g.validate("wheels").empty());
  g.axes_B.col(0) *= 2.0;
  g.inertia_kg_m2[0] = kNaN;
  g.inertia_kg_m2[2] = -1e-4;
  CHECK(g.validate("wheels") == std::vector<std::string>{
                                    "wheels.axes_B: column 0 must be a unit vector",
                                    "wheels.inertia_kg_m2: wheel 0 must be finite and > 0",
                                    "wheels.inertia_kg_m2: wheel 2 must be finite and > 0"});
  CHECK(g.validate("").front() == "axes_B: column 0 must be a unit vector");
  for (const int count : {0, 5}) {
    g.count = count;
    CHECK(g.validate("wheels") == std::vector<std::string>{"wheels.count: must be in 1..4"});
  }
}

TEST_CASE("Validation helpers reject NaN and name the field", "[common][components][validation]") {
  std::vector<std::string> errors;
  flatsat::requirePositive(errors, "a", 1.0);
  flatsat::requireNonNegative(errors, "b", 0.0);
  flatsat::requireFinite(errors, "c", Eigen::Vector3d::Zero());
  flatsat::requireUnit(errors, "d", Eigen::Vector3d(0.0, 1.0 + 0.5e-6, 0.0));
  flatsat::requireAllPositive(errors, "e", Eigen::Vector3d::Ones(), "coil");
  flatsat::requireInRange(errors, "f", 4, 1, 4);
  CHECK(errors.empty());

  flatsat::requirePositive(errors, "a", 0.0);
  flatsat::requirePositive(errors, "a", kNaN);
  flatsat::requireNonNegative(errors, "b", -std::numeric_limits<double>::infinity());
  flatsat::requireNonNegative(errors, "b", kNaN);
  flatsat::requireFinite(errors, "c", Eigen::Vector3d(0.0, kNaN, 0.0));
  flatsat::requireUnit(errors, "d", Eigen::Vector3d(0.0, 1.0 + 2e-6, 0.0));
  flatsat::requireAllPositive(errors, "e", Eigen::Vector3d(1.0, 0.0, 1.0), "coil");
  flatsat::requireInRange(errors, "f", 0, 1, 4);
  CHECK(errors == std::vector<std::string>{"a: must be finite and > 0", "a: must be finite and > 0",
                                           "b: must be finite and >= 0", "b: must be finite and >= 0",
                                           "c: must be finite", "d: must be a unit vector",
                                           "e: every coil must be finite and > 0", "f: must be in 1..4"});
}
