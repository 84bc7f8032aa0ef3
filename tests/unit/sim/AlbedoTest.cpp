// SPDX-License-Identifier: Apache-2.0
// Earth albedo on a plate (sim/Albedo.hpp) against Russell's law for a Lambert sphere.
#include <cmath>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "sim/Albedo.hpp"
#include "sim/Constants.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

TEST_CASE("Albedo far from the Earth follows Russell's phase law for a Lambert sphere", "[sim][albedo]") {
  // 1000 Earth radii: the seen cap is the half sphere to 0.06 deg and the rays are parallel.
  // (At 100 radii the limb the spacecraft cannot see still holds 6 % of a 150 deg crescent.)
  const double r = 1000.0 * kEarthEquatorialRadius_m;
  const Eigen::Vector3d r_m = r * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d toward_earth = -Eigen::Vector3d::UnitX();
  AlbedoParams p;
  p.albedo = 0.3;
  for (const double phase_deg : {0.0, 30.0, 60.0, 90.0, 120.0, 150.0}) {
    // The Sun seen from the Earth at the phase angle from the spacecraft's direction.
    const Eigen::Vector3d sun(std::cos(phase_deg * kDeg), std::sin(phase_deg * kDeg), 0.0);
    const double model = albedoIrradiance(r_m, sun, toward_earth, p);
    const double russell = lambertSphereFarField(r, phase_deg * kDeg, p.albedo);
    INFO("phase " << phase_deg << " deg: model " << model << ", Russell " << russell);
    CHECK(model == Approx(russell).epsilon(0.01).margin(1e-3 * lambertSphereFarField(r, 0.0, p.albedo)));
  }
}

TEST_CASE("Albedo in low orbit: bounded, dark on the night side and behind the plate, converged",
          "[sim][albedo]") {
  const double r = kEarthEquatorialRadius_m + 500e3;
  const Eigen::Vector3d r_m = r * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d nadir = -Eigen::Vector3d::UnitZ();
  AlbedoParams p;
  // Sun at the zenith: a uniform Lambert cap of radiance a E/π could give at most a (R/r)².
  const double overhead = albedoIrradiance(r_m, Eigen::Vector3d::UnitZ(), nadir, p);
  const double ratio = kEarthEquatorialRadius_m / r;
  CHECK(overhead > 0.5 * p.albedo * ratio * ratio);
  CHECK(overhead < p.albedo * ratio * ratio);
  CHECK(albedoIrradiance(r_m, -Eigen::Vector3d::UnitZ(), nadir, p) == 0.0);          // midnight: whole cap dark
  CHECK(albedoIrradiance(r_m, Eigen::Vector3d::UnitZ(), -nadir, p) == 0.0);          // plate faces space
  // Twice the rings and sectors change the result by far less than the model's own simplicity.
  const Eigen::Vector3d sun = Eigen::Vector3d(std::sin(60 * kDeg), 0.0, std::cos(60 * kDeg));
  const Eigen::Vector3d tilted = Eigen::Vector3d(0.5, 0.3, -0.8).normalized();
  AlbedoParams fine = p;
  fine.rings *= 2;
  fine.sectors *= 2;
  CHECK(albedoIrradiance(r_m, sun, tilted, p) == Approx(albedoIrradiance(r_m, sun, tilted, fine)).epsilon(0.005));
}
