// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/Constants.hpp"
#include "sim/PanelModel.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

namespace {

Panel plate(const Eigen::Vector3d& normal, double area, double specular, double diffuse) {
  Panel p;
  p.area_m2 = area;
  p.normal_B = normal;
  p.specular = specular;
  p.diffuse = diffuse;
  p.absorbed = 1.0 - specular - diffuse;
  return p;
}

constexpr double kPressure1Au = 1361.0 / 299792458.0;  // [N/m²] ≈ 4.54e-6

}  // namespace

TEST_CASE("Panel::validate", "[sim][disturbances]") {
  CHECK(plate(Eigen::Vector3d::UnitX(), 1.0, 0.3, 0.2).validate().empty());
  CHECK(anyStartsWith(Panel{}.validate(), "area_m2: 0 must be > 0"));

  Panel p = plate(Eigen::Vector3d(1.0, 1.0, 0.0), 1.0, 0.3, 0.2);
  p.r_cp_B_m.x() = std::numeric_limits<double>::quiet_NaN();
  p.aero_specular = 1.5;
  p.diffuse = 0.3;  // fractions now sum to 1.1
  p.sun_tracking_axis_B = Eigen::Vector3d(0.0, 2.0, 0.0);
  const auto errors = p.validate();
  CHECK(errors.size() == 5);
  CHECK(anyStartsWith(errors, "sun_tracking_axis_B: must be zero or a unit vector (norm 2)"));
  CHECK(anyStartsWith(errors, "normal_B: must be a unit vector"));
  CHECK(anyStartsWith(errors, "r_cp_B_m: must be finite"));
  CHECK(anyStartsWith(errors, "aero_specular: 1.5 not in [0, 1]"));
  CHECK(anyStartsWith(errors, "absorbed: specular + diffuse + absorbed = 1.1 must be 1"));
}

TEST_CASE("Solar flux scales with illumination and the inverse square of the distance", "[sim][disturbances]") {
  CHECK(solarFlux_W_m2(kAstronomicalUnit_m, 1.0) == Approx(1361.0).epsilon(1e-15));
  CHECK(solarFlux_W_m2(0.5 * kAstronomicalUnit_m, 1.0) == Approx(4.0 * 1361.0).epsilon(1e-15));
  CHECK(solarFlux_W_m2(1.0167 * kAstronomicalUnit_m, 0.3) == Approx(0.3 * 1361.0 / (1.0167 * 1.0167)).epsilon(1e-14));
  CHECK(solarFlux_W_m2(kAstronomicalUnit_m, 0.0) == 0.0);
}

TEST_CASE("Solar pressure on a flat plate", "[sim][disturbances]") {
  const Eigen::Vector3d n = Eigen::Vector3d(1.0, -2.0, 2.0) / 3.0;
  const double area = 2.5;
  const double P = kPressure1Au;
  GIVEN("the Sun face-on (ŝ = n)") {
    // Absorbed light pushes with P A, specular doubles the normal momentum,
    // Lambertian re-emission adds 2/3 of it: |F| = (1 + ρs + 2ρd/3) P A.
    CHECK((solarPressureForceTorque(plate(n, area, 0.0, 0.0), n, 1361.0).force_B_N + P * area * n).norm() < 1e-19);
    CHECK((solarPressureForceTorque(plate(n, area, 1.0, 0.0), n, 1361.0).force_B_N + 2.0 * P * area * n).norm() <
          1e-19);
    CHECK((solarPressureForceTorque(plate(n, area, 0.4, 0.0), n, 1361.0).force_B_N + 1.4 * P * area * n).norm() <
          1e-19);
    CHECK((solarPressureForceTorque(plate(n, area, 0.3, 0.3), n, 1361.0).force_B_N + 1.5 * P * area * n).norm() <
          1e-19);
  }
  GIVEN("the Sun 60° off the normal") {
    const Eigen::Vector3d s = Eigen::AngleAxisd(std::numbers::pi / 3, n.unitOrthogonal()) * n;
    THEN("an absorber is pushed along −ŝ by P A cos θ, a mirror along −n by 2 P A cos² θ") {
      CHECK((solarPressureForceTorque(plate(n, area, 0.0, 0.0), s, 1361.0).force_B_N + 0.5 * P * area * s).norm() <
            1e-19);
      CHECK((solarPressureForceTorque(plate(n, area, 1.0, 0.0), s, 1361.0).force_B_N + 0.5 * P * area * n).norm() <
            1e-19);
    }
    THEN("a diffuser gets P A cos θ (ŝ + 2n/3) and twice the flux doubles it") {
      const Eigen::Vector3d expected = -0.5 * P * area * (s + 2.0 / 3.0 * n);
      CHECK((solarPressureForceTorque(plate(n, area, 0.0, 1.0), s, 1361.0).force_B_N - expected).norm() < 1e-19);
      CHECK((solarPressureForceTorque(plate(n, area, 0.0, 1.0), s, 2722.0).force_B_N - 2.0 * expected).norm() <
            1e-19);
    }
  }
  GIVEN("the Sun behind the plate, edge-on, or in eclipse") {
    CHECK(solarPressureForceTorque(plate(n, area, 0.2, 0.2), -n, 1361.0).force_B_N.isZero());
    CHECK(solarPressureForceTorque(plate(n, area, 0.2, 0.2), n.unitOrthogonal(), 1361.0).force_B_N.isZero());
    CHECK(solarPressureForceTorque(plate(n, area, 0.2, 0.2), n, 0.0).force_B_N.isZero());
  }
  GIVEN("a plate offset from the centre of mass") {
    Panel p = plate(Eigen::Vector3d::UnitX(), 1.0, 0.0, 0.0);
    p.r_cp_B_m = Eigen::Vector3d(0.0, 0.5, 0.2);
    const ForceTorque ft = solarPressureForceTorque(p, Eigen::Vector3d::UnitX(), 1361.0);
    // F = −P x̂ at (0, 0.5, 0.2): τ = r × F = −P (0, 0.2, −0.5).
    CHECK((ft.torque_B_Nm - P * Eigen::Vector3d(0.0, -0.2, 0.5)).norm() < 1e-19);
  }
}

TEST_CASE("A sun-tracking panel faces the Sun's projection normal to its drive axis", "[sim][disturbances]") {
  // A black wing on a drive about y, its centre of pressure 8 m out on +y,
  // the Sun at (1, 1, 1)/√3: the wing turns to (1, 0, 1)/√2, so it is lit at
  // cos θ = √(2/3) and takes F = −P A cos θ ŝ (a black plate's pressure).
  Panel wing = plate(Eigen::Vector3d::UnitZ(), 20.0, 0.0, 0.0);
  wing.sun_tracking_axis_B = Eigen::Vector3d::UnitY();
  wing.r_cp_B_m = Eigen::Vector3d(0.0, 8.0, 0.0);
  const Eigen::Vector3d sun = Eigen::Vector3d::Ones().normalized();
  CHECK(wing.normalFacing(sun).isApprox(Eigen::Vector3d(1.0, 0.0, 1.0).normalized(), 1e-15));
  const double flux = 1361.0, P = flux / kSpeedOfLight_m_s;
  const ForceTorque ft = solarPressureForceTorque(wing, sun, flux);
  const Eigen::Vector3d force = -P * 20.0 * std::sqrt(2.0 / 3.0) * sun;
  CHECK((ft.force_B_N - force).norm() < 1e-12 * force.norm());
  CHECK((ft.torque_B_Nm - Eigen::Vector3d(0.0, 8.0, 0.0).cross(force)).norm() < 1e-12 * 8.0 * force.norm());
  // With the Sun behind the mounted face the drive still turns it lit; a
  // fixed plate stays dark. A Sun along the drive axis leaves it as mounted.
  CHECK(solarPressureForceTorque(wing, -sun, flux).force_B_N.norm() > 0.0);
  Panel fixed = wing;
  fixed.sun_tracking_axis_B.setZero();
  CHECK(solarPressureForceTorque(fixed, -Eigen::Vector3d::UnitZ(), flux).force_B_N.isZero());
  CHECK(wing.normalFacing(Eigen::Vector3d::UnitY()) == Eigen::Vector3d::UnitZ());
  // The wind meets the turned wing: face-on air on the Sun's side of it.
  const Eigen::Vector3d toward_sun_face = -Eigen::Vector3d(1.0, 0.0, 1.0).normalized();
  CHECK(aerodynamicForceTorque(wing, 1e-12, 7000.0 * toward_sun_face, sun).force_B_N.norm() > 0.0);
  CHECK(aerodynamicForceTorque(wing, 1e-12, -7000.0 * toward_sun_face, sun).force_B_N.isZero());
}

TEST_CASE("Aerodynamic force on a flat plate in free-molecular flow", "[sim][disturbances]") {
  const double rho = 3e-12;  // [kg/m³] ≈ 500 km
  const double V = 7600.0;
  const Eigen::Vector3d wind(V, 0.0, 0.0);  // air moving along +x relative to the body
  const double q = rho * V * V;             // 2 × dynamic pressure
  GIVEN("an absorbing (fully accommodating) plate facing the flow") {
    const Panel p = plate(-Eigen::Vector3d::UnitX(), 1.2, 0.0, 0.0);
    THEN("the drag is ½ ρ C_D A V² with C_D = 2, along the wind") {
      CHECK((aerodynamicForceTorque(p, rho, wind).force_B_N - Eigen::Vector3d(q * 1.2, 0.0, 0.0)).norm() < 1e-17);
    }
  }
  GIVEN("a plate tilted by α = 40° against the flow") {
    const double alpha = 40.0 * std::numbers::pi / 180.0;
    const Eigen::Vector3d n(-std::cos(alpha), 0.0, std::sin(alpha));
    Panel absorbing = plate(n, 1.2, 0.0, 0.0);
    Panel mirror = absorbing;
    mirror.aero_specular = 1.0;
    THEN("absorbed flow pushes along the wind, ρV²A cos α; specular flow along −n, 2ρV²A cos² α") {
      CHECK((aerodynamicForceTorque(absorbing, rho, wind).force_B_N - q * 1.2 * std::cos(alpha) * Eigen::Vector3d::UnitX())
                .norm() < 1e-17);
      CHECK((aerodynamicForceTorque(mirror, rho, wind).force_B_N + 2.0 * q * 1.2 * std::pow(std::cos(alpha), 2) * n)
                .norm() < 1e-17);
      AND_THEN("a mirror gives lift: its force is not along the wind") {
        CHECK(std::abs(aerodynamicForceTorque(mirror, rho, wind).force_B_N.z()) > 0.1 * q);
      }
    }
  }
  GIVEN("the flow on the back, edge-on, or no air") {
    CHECK(aerodynamicForceTorque(plate(Eigen::Vector3d::UnitX(), 1.0, 0.0, 0.0), rho, wind).force_B_N.isZero());
    CHECK(aerodynamicForceTorque(plate(Eigen::Vector3d::UnitZ(), 1.0, 0.0, 0.0), rho, wind).force_B_N.isZero());
    CHECK(aerodynamicForceTorque(plate(-Eigen::Vector3d::UnitX(), 1.0, 0.0, 0.0), 0.0, wind).force_B_N.isZero());
    CHECK(aerodynamicForceTorque(plate(-Eigen::Vector3d::UnitX(), 1.0, 0.0, 0.0), rho, Eigen::Vector3d::Zero())
              .force_B_N.isZero());
  }
  GIVEN("a 2 m² plate facing the flow, 0.5 m along y and 0.2 m along z from the centre of mass") {
    Panel p = plate(-Eigen::Vector3d::UnitX(), 2.0, 0.0, 0.0);
    p.r_cp_B_m = Eigen::Vector3d(0.0, 0.5, 0.2);
    const ForceTorque ft = aerodynamicForceTorque(p, rho, wind);
    THEN("τ = r × F = 2ρV² (0, 0.2, −0.5): drag turns the offset plate downstream") {
      CHECK((ft.torque_B_Nm - 2.0 * q * Eigen::Vector3d(0.0, 0.2, -0.5)).norm() < 1e-17);
    }
  }
  GIVEN("a closed cube of 1 m² faces centred on the centre of mass") {
    std::vector<Panel> cube;
    for (int axis = 0; axis < 3; ++axis) {
      for (const double sign : {1.0, -1.0}) {
        Panel face = plate(sign * Eigen::Vector3d::Unit(axis), 1.0, 0.0, 0.0);
        face.r_cp_B_m = 0.5 * sign * Eigen::Vector3d::Unit(axis);
        cube.push_back(face);
      }
    }
    const Eigen::Vector3d oblique = V * Eigen::Vector3d(2.0, -1.0, 2.0) / 3.0;
    const ForceTorque ft = aerodynamicForceTorque(cube, rho, oblique);
    THEN("the drag is ρV² times the projected area Σ|ŵ_i| = 5/3 m² and there is no torque") {
      CHECK((ft.force_B_N - q * (5.0 / 3.0) * oblique / V).norm() < 1e-17);
      CHECK(ft.torque_B_Nm.norm() < 1e-19);
    }
  }
}
