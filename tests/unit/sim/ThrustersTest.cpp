// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "sim/Thrusters.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

namespace {

ThrusterParams thruster(const Eigen::Vector3d& r, const Eigen::Vector3d& d, double thrust) {
  ThrusterParams t;
  t.r_B_m = r;
  t.direction_B = d;
  t.thrust_N = thrust;
  return t;
}

// A roll pair on ±y firing ±z, and an axial thruster offset along y.
std::vector<ThrusterParams> threeThrusters() {
  return {thruster({0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 1.0), thruster({0.0, -1.0, 0.0}, {0.0, 0.0, -1.0}, 1.0),
          thruster({-0.5, 0.2, 0.0}, {1.0, 0.0, 0.0}, 2.0)};
}

constexpr double kDt = 0.1;

}  // namespace

TEST_CASE("ThrusterParams::validate", "[sim][actuators]") {
  CHECK(threeThrusters()[0].validate().empty());
  ThrusterParams t = thruster({0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, 0.0);
  t.min_impulse_bit_Ns = -1e-3;
  t.gimballed = true;
  t.gimbal_axis2_B = Eigen::Vector3d::Zero();
  t.gimbal_min_rad = Eigen::Vector2d(0.2, -4.0);
  t.gimbal_max_rad = Eigen::Vector2d(0.1, 0.1);
  const auto errors = t.validate();
  CHECK(anyStartsWith(errors, "direction_B: must be a unit vector"));
  CHECK(anyStartsWith(errors, "thrust_N: 0 must be > 0"));
  CHECK(anyStartsWith(errors, "min_impulse_bit_Ns: -0.001 must be ≥ 0"));
  CHECK(anyStartsWith(errors, "gimbal_axis2_B: must be a unit vector"));
  CHECK(anyStartsWith(errors, "gimbal_max_rad[0]: must be ≥ gimbal_min_rad[0]"));
  CHECK(anyStartsWith(errors, "gimbal_min_rad[1]: -4 must be finite and ≥ −π"));
  CHECK(errors.size() == 6);
}

TEST_CASE("Thruster force and torque are Σ F_i and Σ r_i × F_i", "[sim][actuators]") {
  const Thrusters set(threeThrusters());
  ThrusterVector on = ThrusterVector::Zero();
  WHEN("all three fire for the whole step") {
    on.head<3>().setConstant(kDt);
    const ThrusterOutput out = set.fire(on, ThrusterGimbals::Zero(), kDt);
    THEN("the roll pair is a pure couple, the axial thruster a force plus a yaw torque") {
      // Pair: F = ±ẑ at ±ŷ: r × F = ŷ × ẑ + (−ŷ) × (−ẑ) = 2x̂ N m, no net force.
      // Axial: F = 2x̂ at (−0.5, 0.2, 0): r × F = (0, 0, −0.4) N m.
      CHECK((out.force_B_N - Eigen::Vector3d(2.0, 0.0, 0.0)).norm() < 1e-15);
      CHECK((out.torque_B_Nm - Eigen::Vector3d(2.0, 0.0, -0.4)).norm() < 1e-15);
      CHECK(out.impulse_Ns.head<3>().isApprox(Eigen::Vector3d(0.1, 0.1, 0.2), 1e-15));
      CHECK(out.on_time_s.tail<kMaxThrusters - 3>().isZero());
    }
  }
  WHEN("only thruster 1 fires, for 30 ms of a 100 ms step") {
    on(0) = 0.03;
    const ThrusterOutput out = set.fire(on, ThrusterGimbals::Zero(), kDt);
    THEN("the step sees the mean 0.3 of its force and torque, and its 0.03 N s impulse") {
      CHECK((out.force_B_N - Eigen::Vector3d(0.0, 0.0, 0.3)).norm() < 1e-15);
      CHECK((out.torque_B_Nm - Eigen::Vector3d(0.3, 0.0, 0.0)).norm() < 1e-15);
      CHECK(out.impulse_Ns(0) == Approx(0.03).epsilon(1e-15));
    }
  }
  WHEN("on-times are negative, too long or not finite") {
    on(0) = -0.05;
    on(1) = 0.5;
    on(2) = std::numeric_limits<double>::quiet_NaN();
    const ThrusterOutput out = set.fire(on, ThrusterGimbals::Zero(), kDt);
    THEN("they are cut to [0, dt] and NaN counts as off") {
      CHECK(out.on_time_s.head<3>() == Eigen::Vector3d(0.0, kDt, 0.0));
      CHECK((out.force_B_N - Eigen::Vector3d(0.0, 0.0, -1.0)).norm() < 1e-15);
    }
  }
}

TEST_CASE("The minimum impulse bit quantises the delivered impulse", "[sim][actuators]") {
  ThrusterParams t = thruster({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, 0.5);
  t.min_impulse_bit_Ns = 0.01;  // t_min = 20 ms
  const Thrusters set({t});
  const auto delivered = [&](double on_time) {
    ThrusterVector on = ThrusterVector::Zero();
    on(0) = on_time;
    return set.fire(on, ThrusterGimbals::Zero(), kDt).impulse_Ns(0);
  };
  CHECK(delivered(0.019) == 0.0);  // shorter than the minimum pulse: nothing
  CHECK(delivered(0.02) == Approx(0.01).epsilon(1e-15));
  CHECK(delivered(3 * 0.02) == Approx(0.03).epsilon(1e-15));  // 0.06 / 0.02 may round just below 3
  CHECK(delivered(0.055) == Approx(0.02).epsilon(1e-15));
  CHECK(delivered(kDt) == Approx(0.05).epsilon(1e-15));
  GIVEN("no minimum impulse bit") {
    const Thrusters continuous({thruster({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, 0.5)});
    ThrusterVector on = ThrusterVector::Zero();
    on(0) = 1e-4;
    CHECK(continuous.fire(on, ThrusterGimbals::Zero(), kDt).impulse_Ns(0) == Approx(5e-5).epsilon(1e-15));
  }
}

TEST_CASE("A failed thruster delivers nothing, the others are unaffected", "[sim][actuators]") {
  std::vector<ThrusterParams> params = threeThrusters();
  params[1].failed = true;
  const Thrusters set(params);
  ThrusterVector on = ThrusterVector::Zero();
  on.head<3>().setConstant(kDt);
  const ThrusterOutput out = set.fire(on, ThrusterGimbals::Zero(), kDt);
  CHECK(out.impulse_Ns(1) == 0.0);
  CHECK(out.on_time_s(1) == 0.0);
  // Left: +ẑ at ŷ (x̂ N m, ẑ N) and the axial thruster.
  CHECK((out.force_B_N - Eigen::Vector3d(2.0, 0.0, 1.0)).norm() < 1e-15);
  CHECK((out.torque_B_Nm - Eigen::Vector3d(1.0, 0.0, -0.4)).norm() < 1e-15);
}

TEST_CASE("A gimbal turns the thrust line off the centre of mass", "[sim][actuators]") {
  // S3-like: thruster below the centre of mass firing +z through it; outer gimbal
  // axis x, inner axis y, ±0.2 rad each.
  ThrusterParams t = thruster({0.0, 0.0, -1.5}, {0.0, 0.0, 1.0}, 0.1);
  t.gimballed = true;
  t.gimbal_axis1_B = Eigen::Vector3d::UnitX();
  t.gimbal_axis2_B = Eigen::Vector3d::UnitY();
  t.gimbal_min_rad = Eigen::Vector2d(-0.2, -0.2);
  t.gimbal_max_rad = Eigen::Vector2d(0.2, 0.2);
  const Thrusters set({t});
  ThrusterVector on = ThrusterVector::Zero();
  on(0) = kDt;

  WHEN("the angles are (a, b) = (0.1, −0.15) rad") {
    const double a = 0.1;
    const double b = -0.15;
    ThrusterGimbals gimbal = ThrusterGimbals::Zero();
    gimbal.col(0) << a, b;
    const ThrusterOutput out = set.fire(on, gimbal, kDt);
    THEN("d = R_x(a) R_y(b) ẑ = (sin b, −sin a cos b, cos a cos b), τ = r × F") {
      const Eigen::Vector3d d(std::sin(b), -std::sin(a) * std::cos(b), std::cos(a) * std::cos(b));
      CHECK((out.force_B_N - 0.1 * d).norm() < 1e-16);
      // r = (0, 0, −1.5): r × d = (1.5 d_y, −1.5 d_x, 0).
      CHECK((out.torque_B_Nm - 0.1 * Eigen::Vector3d(1.5 * d.y(), -1.5 * d.x(), 0.0)).norm() < 1e-16);
      CHECK(out.gimbal_rad.col(0) == Eigen::Vector2d(a, b));
    }
  }
  WHEN("the angles are beyond the limits or not finite") {
    ThrusterGimbals gimbal = ThrusterGimbals::Zero();
    gimbal.col(0) << 0.5, std::numeric_limits<double>::infinity();
    const ThrusterOutput out = set.fire(on, gimbal, kDt);
    THEN("they are held at the limit, a non-finite one at zero") {
      CHECK(out.gimbal_rad.col(0) == Eigen::Vector2d(0.2, 0.0));
      CHECK(out.torque_B_Nm.x() == Approx(0.1 * 1.5 * -std::sin(0.2)).epsilon(1e-14));
    }
  }
  WHEN("the thruster is not fired") {
    ThrusterGimbals gimbal = ThrusterGimbals::Zero();
    gimbal.col(0) << 0.1, 0.1;
    const ThrusterOutput out = set.fire(ThrusterVector::Zero(), gimbal, kDt);
    THEN("the gimbal still reports its angles, with no force") {
      CHECK(out.gimbal_rad.col(0) == Eigen::Vector2d(0.1, 0.1));
      CHECK(out.force_B_N.isZero());
    }
  }
}
