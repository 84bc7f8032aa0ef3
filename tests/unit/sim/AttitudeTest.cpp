// SPDX-License-Identifier: Apache-2.0
#include <cmath>

#include <catch2/catch.hpp>

#include "sim/Attitude.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

TEST_CASE("skew builds the cross-product matrix", "[sim][attitude]") {
  const Eigen::Vector3d a(0.3, -1.2, 2.5);
  const Eigen::Vector3d b(-0.7, 0.4, 1.1);
  CHECK((skew(a) * b - a.cross(b)).norm() < 1e-15);
  CHECK((skew(a) + skew(a).transpose()).norm() == 0.0);
}

TEST_CASE("quatFromRotationVector is the exponential map", "[sim][attitude]") {
  GIVEN("a quarter turn about z") {
    const Eigen::Quaterniond q = quatFromRotationVector(Eigen::Vector3d(0.0, 0.0, kPi / 2.0));
    THEN("it is (cos π/4, 0, 0, sin π/4) and turns x into y") {
      CHECK(q.w() == Approx(std::sqrt(0.5)).epsilon(1e-15));
      CHECK(q.z() == Approx(std::sqrt(0.5)).epsilon(1e-15));
      CHECK((q * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm() < 1e-15);
    }
  }
  GIVEN("a tiny rotation vector") {
    const Eigen::Vector3d phi(1e-10, -2e-10, 3e-10);
    const Eigen::Quaterniond q = quatFromRotationVector(phi);
    THEN("the quaternion is (1, φ/2) to double precision and unit") {
      CHECK(q.w() == 1.0);
      CHECK((q.vec() - 0.5 * phi).norm() < 1e-25);
      CHECK(q.norm() == Approx(1.0).epsilon(1e-16));
    }
  }
  GIVEN("a rotation just above the small-angle switch") {
    const Eigen::Vector3d phi = 1.1e-6 * Eigen::Vector3d(1.0, 2.0, -2.0).normalized();
    const Eigen::Quaterniond q = quatFromRotationVector(phi);
    THEN("it agrees with (cos θ/2, sin θ/2 · axis)") {
      CHECK(q.w() == Approx(std::cos(0.55e-6)).epsilon(1e-16));
      CHECK((q.vec() - std::sin(0.55e-6) * phi.normalized()).norm() < 1e-22);
    }
  }
}

TEST_CASE("rotationVectorFromQuat inverts the exponential map", "[sim][attitude]") {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.2, -0.5, 0.8).normalized();
  for (const double angle : {0.0, 1e-12, 1e-7, 1e-3, 0.5, 2.0, kPi - 1e-6}) {
    const Eigen::Vector3d phi = angle * axis;
    CHECK((rotationVectorFromQuat(quatFromRotationVector(phi)) - phi).norm() <= 1e-14 * std::max(1.0, angle));
  }
  GIVEN("q and −q") {
    const Eigen::Quaterniond q = quatFromRotationVector(1.3 * axis);
    const Eigen::Quaterniond minus_q(-q.w(), -q.x(), -q.y(), -q.z());
    CHECK((rotationVectorFromQuat(minus_q) - 1.3 * axis).norm() < 1e-14);
  }
  GIVEN("a rotation by 3π/2") {
    const Eigen::Quaterniond q = quatFromRotationVector(Eigen::Vector3d(0.0, 0.0, 1.5 * kPi));
    THEN("the log returns the shorter −π/2 rotation") {
      CHECK((rotationVectorFromQuat(q) - Eigen::Vector3d(0.0, 0.0, -0.5 * kPi)).norm() < 1e-14);
    }
  }
}

TEST_CASE("quatDerivative follows q̇ = ½ q ⊗ (0, ω)", "[sim][attitude]") {
  GIVEN("identity attitude spinning about z") {
    const Eigen::Quaterniond dq = quatDerivative(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.0, 0.0, 0.4));
    CHECK(dq.w() == 0.0);
    CHECK((dq.vec() - Eigen::Vector3d(0.0, 0.0, 0.2)).norm() < 1e-16);
  }
  GIVEN("a general attitude and body rate") {
    const Eigen::Quaterniond q0 = quatFromRotationVector(Eigen::Vector3d(0.3, -1.1, 0.6));
    const Eigen::Vector3d w(0.05, -0.02, 0.08);
    // q(t) = q0 ⊗ exp(ω t) for a constant body rate; central difference at t = 0.
    const double dt = 1e-4;
    const Eigen::Vector4d numeric =
        ((q0 * quatFromRotationVector(w * dt)).coeffs() - (q0 * quatFromRotationVector(-w * dt)).coeffs()) / (2.0 * dt);
    const Eigen::Quaterniond dq = quatDerivative(q0, w);
    CHECK((dq.coeffs() - numeric).norm() < 1e-12);
    THEN("the derivative is orthogonal to q (the norm is preserved)") {
      CHECK(std::abs(dq.coeffs().dot(q0.coeffs())) < 1e-17);
    }
  }
}

TEST_CASE("angleBetween is accurate at all angles", "[sim][attitude]") {
  CHECK(angleBetween(Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()) == Approx(kPi / 2.0).epsilon(1e-15));
  CHECK(angleBetween(Eigen::Vector3d(2.0, 0.0, 0.0), Eigen::Vector3d(5.0, 0.0, 0.0)) == 0.0);
  CHECK(angleBetween(Eigen::Vector3d::UnitZ(), -3.0 * Eigen::Vector3d::UnitZ()) == Approx(kPi).epsilon(1e-15));
  // acos(a·b/|a||b|) would return exactly 0 here.
  CHECK(angleBetween(Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Vector3d(1.0, 1e-9, 0.0)) == Approx(1e-9).epsilon(1e-9));
  CHECK(angleBetween(Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Vector3d(-1.0, 1e-9, 0.0)) ==
        Approx(kPi - 1e-9).epsilon(1e-15));
}
