// SPDX-License-Identifier: Apache-2.0
#include <cmath>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/Disturbances.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

TEST_CASE("gravity-gradient torque vanishes along principal axes", "[sim][disturbance]") {
  const Eigen::Matrix3d J = Eigen::Vector3d(2.0, 3.0, 4.0).asDiagonal();
  const double r = 6938e3;
  for (int k = 0; k < 3; ++k) {
    CHECK(gravityGradientTorque_B_Nm(r * Eigen::Vector3d::Unit(k), J).norm() == 0.0);
    CHECK(gravityGradientTorque_B_Nm(-r * Eigen::Vector3d::Unit(k), J).norm() == 0.0);
  }
  GIVEN("a body with equal principal moments") {
    CHECK(gravityGradientTorque_B_Nm(Eigen::Vector3d(3e6, -4e6, 5e6), 2.5 * Eigen::Matrix3d::Identity()).norm() <
          1e-20);
  }
}

TEST_CASE("gravity-gradient torque for a pitch offset in the orbit plane", "[sim][disturbance]") {
  // Orbit frame: x radial (zenith), y orbit normal. The body starts with its
  // principal x axis on the radial and is turned by +θ about y; the radial unit
  // vector in body axes is then R_y(θ)ᵀ x̂ = (cos θ, 0, sin θ).
  //
  // Sign from energy: MacCullagh's potential of the body is, up to constants,
  //   V(θ) = (3μ/2r³) r̂ᵀ J r̂ = (3μ/2r³)(Jx cos²θ + Jz sin²θ),
  // and the torque about +y is −dV/dθ = −(3μ/2r³)(Jz − Jx) sin 2θ: with Jz > Jx it
  // turns the body back to θ = 0 (minimum-inertia axis to the vertical).
  const double Jx = 2.0;
  const double Jz = 4.0;
  const Eigen::Matrix3d J = Eigen::Vector3d(Jx, 3.0, Jz).asDiagonal();
  const double r = 7000e3;
  const auto potential = [&](double theta) {
    const Eigen::Vector3d u(std::cos(theta), 0.0, std::sin(theta));
    return 1.5 * kMu / std::pow(r, 3) * u.dot(J * u);
  };

  for (const double theta : {0.1, 0.5, 1.0, -0.7, 2.0}) {
    const Eigen::Vector3d tau =
        gravityGradientTorque_B_Nm(r * Eigen::Vector3d(std::cos(theta), 0.0, std::sin(theta)), J);
    const double expected = -1.5 * kMu / std::pow(r, 3) * (Jz - Jx) * std::sin(2.0 * theta);
    CHECK(tau.y() == Approx(expected).epsilon(1e-13));
    CHECK(std::abs(tau.x()) < 1e-25);
    CHECK(std::abs(tau.z()) < 1e-25);
    const double h = 1e-6;
    CHECK(tau.y() == Approx(-(potential(theta + h) - potential(theta - h)) / (2.0 * h)).epsilon(1e-7));
  }
  THEN("the torque is restoring for small offsets") {
    CHECK(gravityGradientTorque_B_Nm(r * Eigen::Vector3d(std::cos(0.01), 0.0, std::sin(0.01)), J).y() < 0.0);
    CHECK(gravityGradientTorque_B_Nm(r * Eigen::Vector3d(std::cos(-0.01), 0.0, std::sin(-0.01)), J).y() > 0.0);
  }
}

TEST_CASE("gravity-gradient torque transforms as a vector and scales with 1/r³", "[sim][disturbance]") {
  Eigen::Matrix3d J;
  J << 2.0, 0.05, -0.03,  //
      0.05, 2.5, 0.02,    //
      -0.03, 0.02, 3.0;
  const Eigen::Vector3d r(3e6, -4e6, 5e6);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.8, Eigen::Vector3d(1.0, 2.0, -1.0).normalized()).toRotationMatrix();
  const Eigen::Vector3d tau = gravityGradientTorque_B_Nm(r, J);
  CHECK((gravityGradientTorque_B_Nm(R * r, R * J * R.transpose()) - R * tau).norm() < 1e-12 * tau.norm());
  CHECK((gravityGradientTorque_B_Nm(2.0 * r, J) - tau / 8.0).norm() < 1e-14 * tau.norm());
  CHECK((gravityGradientTorque_B_Nm(r, J, 2.0 * kMu) - 2.0 * tau).norm() < 1e-14 * tau.norm());
}
