// SPDX-License-Identifier: Apache-2.0
// Seed S2 flaps (FR2718105 / CN1148836) against an independent panel-force
// integration: the flaps are four two-sided specular plates of the panel model.
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/Flaps.hpp"
#include "sim/PanelModel.hpp"

using namespace flatsat::sim;

namespace {

constexpr double kRho = 4e-11;  // [kg/m³] ≈ 300 km
constexpr double kV = 7700.0;   // [m/s]
constexpr double kArea = 0.25;  // [m²] one plate, the seed's S/2
constexpr double kArm = 1.6;    // [m] l

FlapsParams seedFlaps() {
  FlapsParams p;
  p.fitted = true;
  p.plate_area_m2 = kArea;
  p.lever_arm_m = kArm;
  p.max_angle_rad = std::numbers::pi / 2;
  return p;
}

// The geometry as stated, built without Flaps: plates 1, 3 on the +wing wing and 2, 4
// on the −wing wing at ±l·wing; θi turns plate i about its wing's outward axis from
// the neutral plane (normal `neutral`, edge-on to the wind); both faces exposed,
// specular molecules. The seed's polar layout: wings along y, neutral normal z.
std::vector<Panel> platesByHand(const Eigen::Vector4d& theta, const Eigen::Vector3d& wing = Eigen::Vector3d::UnitY(),
                                const Eigen::Vector3d& neutral = Eigen::Vector3d::UnitZ()) {
  std::vector<Panel> faces;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d outward = (i % 2 == 0 ? 1.0 : -1.0) * wing;
    for (const double side : {1.0, -1.0}) {
      Panel face;
      face.area_m2 = kArea;
      face.normal_B = side * (Eigen::AngleAxisd(theta(i), outward) * neutral);
      face.r_cp_B_m = kArm * outward;
      face.aero_specular = 1.0;
      faces.push_back(face);
    }
  }
  return faces;
}

const Eigen::Vector3d kWind = kV * Eigen::Vector3d::UnitX();  // body x points against the motion

}  // namespace

TEST_CASE("FlapsParams::validate", "[sim][actuators]") {
  CHECK(FlapsParams{}.validate().empty());  // not fitted
  CHECK(seedFlaps().validate().empty());
  FlapsParams p = seedFlaps();
  p.plate_area_m2 = -1.0;
  p.lever_arm_m = std::numeric_limits<double>::quiet_NaN();
  p.max_angle_rad = 2.0;
  p.aero_specular = 1.2;
  const auto errors = p.validate();
  REQUIRE(errors.size() == 4);
  CHECK(errors[0].rfind("plate_area_m2: -1", 0) == 0);
  CHECK(errors[1].rfind("lever_arm_m: nan", 0) == 0);
  CHECK(errors[2].rfind("max_angle_rad: 2 not in (0, π/2]", 0) == 0);
  CHECK(errors[3].rfind("aero_specular: 1.2 not in [0, 1]", 0) == 0);
}

TEST_CASE("Flap torques: closed form against panel integration", "[sim][actuators]") {
  const Flaps flaps(seedFlaps());
  const double scale = 2.0 * kRho * kArea * kV * kV * kArm;  // 2ρA_pV²l = K/2 with the seed's K = 2ρSV²l, S = 2A_p
  const std::vector<Eigen::Vector4d> angle_sets = {
      {0.3, -0.2, 0.0, 0.7}, {-1.2, 0.4, 0.9, -0.05}, {1.5707, -1.5707, 0.6, 0.6}, {0.01, 0.02, -0.03, 0.04}};
  for (const Eigen::Vector4d& theta : angle_sets) {
    const ForceTorque by_hand = aerodynamicForceTorque(platesByHand(theta), kRho, kWind);
    const auto panels = flaps.panels(theta);
    const ForceTorque by_flaps = aerodynamicForceTorque(panels, kRho, kWind);
    const Eigen::Vector2d c = Flaps::normalisedTorques(theta);
    // Per plate: lift 2ρA_pV² sin θ cos θ |sin θ| along z, drag 2ρA_pV² |sin θ|³ along x.
    double c_ax = 0.0;
    double c_az = 0.0;
    double drag = 0.0;
    for (int i = 0; i < 4; ++i) {
      const double s = std::abs(std::sin(theta(i)));
      c_ax += std::sin(theta(i)) * std::cos(theta(i)) * s;
      c_az += (i % 2 == 0 ? -1.0 : 1.0) * s * s * s;  // (−1)^i, seed numbering 1..4
      drag += 2.0 * kRho * kArea * kV * kV * s * s * s;
    }
    CHECK(c(0) == Approx(c_ax).margin(1e-15));
    CHECK(c(1) == Approx(c_az).margin(1e-15));
    const double tolerance = 1e-12 * scale;
    CHECK((by_hand.torque_B_Nm - scale * Eigen::Vector3d(c_ax, 0.0, c_az)).norm() < tolerance);
    CHECK((by_flaps.torque_B_Nm - by_hand.torque_B_Nm).norm() < tolerance);
    CHECK((flaps.nominalTorque_B_Nm(theta, kRho, kV) - by_hand.torque_B_Nm).norm() < tolerance);
    CHECK(by_hand.force_B_N.x() == Approx(drag).epsilon(1e-12));
  }
}

TEST_CASE("Flap modes of the seed", "[sim][actuators]") {
  const Flaps flaps(seedFlaps());
  const double scale = 2.0 * kRho * kArea * kV * kV * kArm;
  const double theta = 0.4;
  const double s3 = std::pow(std::sin(theta), 3);

  GIVEN("the drag-only mode θ1 = −θ3 = θ2 = −θ4") {
    const ForceTorque ft = aerodynamicForceTorque(platesByHand({theta, theta, -theta, -theta}), kRho, kWind);
    THEN("no torque, no lift, and a drag 4 · 2ρA_pV² |sin θ|³") {
      CHECK(ft.torque_B_Nm.norm() < 1e-15 * scale);
      CHECK(std::abs(ft.force_B_N.z()) < 1e-15 * scale);
      CHECK(ft.force_B_N.x() == Approx(8.0 * kRho * kArea * kV * kV * s3).epsilon(1e-13));
      CHECK(Flaps::normalisedTorques({theta, theta, -theta, -theta}).norm() < 1e-16);
    }
  }
  GIVEN("one wing's plates turned opposite, θ2 = −θ4 (the −y wing)") {
    const ForceTorque ft = aerodynamicForceTorque(platesByHand({0.0, theta, 0.0, -theta}), kRho, kWind);
    THEN("pure yaw +z from the one-sided drag, c_az = 2|sin θ|³, no lift") {
      CHECK((ft.torque_B_Nm - scale * Eigen::Vector3d(0.0, 0.0, 2.0 * s3)).norm() < 1e-12 * scale);
      CHECK(std::abs(ft.force_B_N.z()) < 1e-15 * scale);
    }
  }
  GIVEN("one plate on each wing turned the same way, θ1 = θ2") {
    const ForceTorque ft = aerodynamicForceTorque(platesByHand({theta, theta, 0.0, 0.0}), kRho, kWind);
    THEN("pure roll, c_ax = sin 2θ |sin θ|: the wings' lifts oppose, their drags balance") {
      const double c_ax = std::sin(2.0 * theta) * std::abs(std::sin(theta));
      CHECK((ft.torque_B_Nm - scale * Eigen::Vector3d(c_ax, 0.0, 0.0)).norm() < 1e-12 * scale);
      CHECK(std::abs(ft.force_B_N.z()) < 1e-15 * scale);
    }
  }
}

TEST_CASE("The seed's inversion assumes c_ax with the factor ½", "[sim][actuators]") {
  // Seed rule 1°a (c_az ≥ 0, C2 = c_az² / |c_ax|³ ≤ 1): θ3 = θ4 = 0 and
  // |sin θ1|, |sin θ2| = |c_ax|^½ [½ ∓ ½ (1 − 4X²)^½]^½, X = −½ + cos(arccos(1 − 2C2)/3).
  // They satisfy sin²θ1 + sin²θ2 = |c_ax| and sin³θ2 − sin³θ1 = c_az exactly, so the
  // round trip holds to O(θ²) for c_ax = Σ ½ sin 2θ |sin θ| (≈ Σ sin²θ sgn θ) and
  // would be off by 2 with algorithms.md's Σ sin 2θ |sin θ|.
  const double c_ax = -2e-3;
  const double c_az = 5e-5;
  const double C2 = c_az * c_az / std::pow(std::abs(c_ax), 3);
  REQUIRE(C2 <= 1.0);
  const double X = -0.5 + std::cos(std::acos(1.0 - 2.0 * C2) / 3.0);
  const double root = std::sqrt(1.0 - 4.0 * X * X);
  const double sign = c_ax < 0.0 ? -1.0 : 1.0;
  const double theta1 = sign * std::asin(std::sqrt(std::abs(c_ax) * (0.5 - 0.5 * root)));
  const double theta2 = sign * std::asin(std::sqrt(std::abs(c_ax) * (0.5 + 0.5 * root)));
  const Eigen::Vector2d c = Flaps::normalisedTorques({theta1, theta2, 0.0, 0.0});
  CHECK(c(1) == Approx(c_az).epsilon(1e-10));
  CHECK(c(0) == Approx(c_ax).epsilon(2e-3));  // cos θ ≈ 1 − 1e-3 at θ ≈ 0.045

  GIVEN("rule 2°a (|c_ax| ≈ 0, c_az ≥ 0): θ2 = −θ4, |sin θ| = (c_az / 2)^⅓") {
    const double t = std::asin(std::cbrt(c_az / 2.0));
    const Eigen::Vector2d back = Flaps::normalisedTorques({0.0, t, 0.0, -t});
    CHECK(std::abs(back(0)) < 1e-18);
    CHECK(back(1) == Approx(c_az).epsilon(1e-12));
  }
}

TEST_CASE("Flaps on wings along yaw z (claim 8, equatorial orbit): roll and pitch, never yaw", "[sim][actuators]") {
  // Seed Fig. 4: the plates extend along the yaw axis and turn about it. Built by hand:
  // plates 1, 3 on the +z wing, 2, 4 on the −z wing at (0, 0, ±l), edge-on in the x–z plane
  // at θ = 0, θi about the wing's outward axis; both faces exposed, specular molecules.
  FlapsParams p = seedFlaps();
  p.wings = FlapWings::kAlongZ;
  const Flaps flaps(p);
  const double scale = 2.0 * kRho * kArea * kV * kV * kArm;
  const std::vector<Eigen::Vector4d> angle_sets = {
      {0.3, -0.2, 0.0, 0.7}, {-1.2, 0.4, 0.9, -0.05}, {0.0, 0.4, 0.0, -0.4}, {0.01, 0.02, -0.03, 0.04}};
  for (const Eigen::Vector4d& theta : angle_sets) {
    const ForceTorque by_hand =
        aerodynamicForceTorque(platesByHand(theta, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()), kRho, kWind);
    const auto panels = flaps.panels(theta);
    const ForceTorque by_flaps = aerodynamicForceTorque(panels, kRho, kWind);
    // The drag of the +z wing (plates 1, 3) along +x at (0, 0, l) pitches +y: (0, 0, l) × (D, 0, 0).
    double c_ax = 0.0;
    double pitch = 0.0;
    for (int i = 0; i < 4; ++i) {
      const double s = std::abs(std::sin(theta(i)));
      c_ax += std::sin(theta(i)) * std::cos(theta(i)) * s;
      pitch += (i % 2 == 0 ? 1.0 : -1.0) * s * s * s;
    }
    const double tolerance = 1e-12 * scale;
    CHECK((by_hand.torque_B_Nm - scale * Eigen::Vector3d(c_ax, pitch, 0.0)).norm() < tolerance);
    CHECK((by_flaps.torque_B_Nm - by_hand.torque_B_Nm).norm() < tolerance);
    CHECK((flaps.nominalTorque_B_Nm(theta, kRho, kV) - by_hand.torque_B_Nm).norm() < tolerance);
    CHECK((scale * flapTorqueShape_B(Flaps::normalisedTorques(theta), FlapWings::kAlongZ) - by_hand.torque_B_Nm).norm() <
          tolerance);
    // Every plate's centre of pressure is on the z axis: whatever the wind's direction and
    // the force it gives, no arm about z, no yaw.
    for (const Eigen::Vector3d& wind : {Eigen::Vector3d(kV, 300.0, -500.0), Eigen::Vector3d(kV, -800.0, 200.0)}) {
      CHECK(std::abs(aerodynamicForceTorque(panels, kRho, wind).torque_B_Nm.z()) < 1e-15 * scale);
    }
  }
  CHECK(flapSecondAxis_B(FlapWings::kAlongY) == Eigen::Vector3d::UnitZ());
  CHECK(flapSecondAxis_B(FlapWings::kAlongZ) == -Eigen::Vector3d::UnitY());
  CHECK(flapWingsFromName("z") == FlapWings::kAlongZ);
  CHECK_FALSE(flapWingsFromName("x").has_value());
}

TEST_CASE("Flap angle commands are limited", "[sim][actuators]") {
  FlapsParams p = seedFlaps();
  p.max_angle_rad = 0.5;
  const Flaps flaps(p);
  const Eigen::Vector4d limited =
      flaps.limitAngles({0.7, -0.9, 0.2, std::numeric_limits<double>::quiet_NaN()});
  CHECK(limited == Eigen::Vector4d(0.5, -0.5, 0.2, 0.0));
}
