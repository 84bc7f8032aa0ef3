// SPDX-License-Identifier: Apache-2.0
// The coarse cosine sun sensor: cell outputs, the least-squares Sun vector of
// opposite pairs, noise statistics, eclipse, and the albedo bias toward the Earth.
#include <cmath>
#include <numbers>
#include <random>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "components/sun_sensor/SunSensorModel.hpp"
#include "sim/Constants.hpp"

using namespace flatsat;
using sun_sensor::SunSensorInput;
using sun_sensor::SunSensorKind;
using sun_sensor::SunSensorModel;
using sun_sensor::SunSensorParams;

namespace {

SunSensorParams coarse(double noise) {
  SunSensorParams p;
  p.kind = SunSensorKind::kCoarseCosine;
  p.cell_noise = noise;
  return p;
}

}  // namespace

TEST_CASE("coarse sun sensor: cosine cells and the exact Sun direction from opposite pairs", "[sun_sensor]") {
  // A 6-face cube and an 8-cell array of four pairs tilted 30 deg off the axes.
  SunSensorParams cube = coarse(0.0);
  SunSensorParams tilted = coarse(0.0);
  tilted.cell_normals_B.clear();
  for (const double az : {0.0, 90.0, 180.0, 270.0}) {
    const double a = az * std::numbers::pi / 180.0;
    const Eigen::Vector3d n(std::cos(a) * std::sin(std::numbers::pi / 3), std::sin(a) * std::sin(std::numbers::pi / 3),
                            std::cos(std::numbers::pi / 3));
    tilted.cell_normals_B.push_back(n);
    tilted.cell_normals_B.push_back(-n);
  }
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  for (const auto& p : {cube, tilted}) {
    SunSensorModel sensor(p);
    for (int k = 0; k < 500; ++k) {
      const Eigen::Vector3d s = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
      SunSensorInput in;
      in.sun_B_unit = s;
      in.flux_ratio = 0.97;  // aphelion
      const auto out = sensor.step(in, 0);
      REQUIRE(out.valid);
      CHECK((out.sun_B_unit - s).norm() < 1e-12);
      REQUIRE(out.cell_count == static_cast<int>(p.cell_normals_B.size()));
      for (int i = 0; i < out.cell_count; ++i) {
        CHECK(out.cell_output[static_cast<std::size_t>(i)] ==
              Approx(0.97 * std::max(0.0, p.cell_normals_B[static_cast<std::size_t>(i)].dot(s))).margin(1e-15));
      }
    }
  }
}

TEST_CASE("coarse sun sensor: cell noise as set, no Sun in eclipse", "[sun_sensor]") {
  SunSensorModel sensor(coarse(0.01));
  SunSensorInput in;
  in.sun_B_unit = Eigen::Vector3d(1.0, 2.0, 2.0).normalized();  // lights +x, +y, +z
  constexpr int kSamples = 100000;
  double sum = 0.0, sum2 = 0.0;
  for (int k = 0; k < kSamples; ++k) {
    const double e = sensor.step(in, 0).cell_output[1] - 0.0;  // -x: dark, noise alone
    sum += e;
    sum2 += e * e;
  }
  const double mean = sum / kSamples;
  CHECK(std::sqrt(sum2 / kSamples - mean * mean) == Approx(0.01).epsilon(0.03));
  in.flux_ratio = 0.0;  // umbra
  CHECK_FALSE(sensor.step(in, 0).valid);
}

TEST_CASE("coarse sun sensor: Earth albedo pulls the estimate toward the Earth, eclipse stays dark",
          "[sun_sensor][albedo]") {
  SunSensorParams p = coarse(0.0);
  p.albedo = sim::AlbedoParams{};
  SunSensorModel with_albedo(p);
  SunSensorModel without(coarse(0.0));
  SunSensorInput in;
  // 500 km over the day side, the Sun 60 deg from the zenith (body z up).
  in.r_B_m = (sim::kEarthEquatorialRadius_m + 500e3) * Eigen::Vector3d::UnitZ();
  in.sun_B_unit = Eigen::Vector3d(std::sin(M_PI / 3), 0.0, std::cos(M_PI / 3));
  const auto clean = without.step(in, 0);
  const auto biased = with_albedo.step(in, 0);
  REQUIRE(biased.valid);
  const double error_deg = std::acos(std::clamp(biased.sun_B_unit.dot(in.sun_B_unit), -1.0, 1.0)) * 180.0 / M_PI;
  INFO("albedo error " << error_deg << " deg");
  CHECK((clean.sun_B_unit - in.sun_B_unit).norm() < 1e-12);
  CHECK(error_deg > 2.0);   // a coarse sensor's classic error: tens of percent of its signal
  CHECK(error_deg < 30.0);
  CHECK(biased.sun_B_unit.z() < in.sun_B_unit.z());  // toward the Earth (body −z)
  CHECK(biased.cell_output[5] > 0.0);                // the nadir cell sees the lit Earth
  in.flux_ratio = 0.0;                               // in the Earth's shadow, the cap half lit
  in.sun_B_unit = Eigen::Vector3d(-1.0, 0.0, -0.2).normalized();
  CHECK_FALSE(with_albedo.step(in, 0).valid);
}

TEST_CASE("coarse sun sensor: an array without opposite pairs or spanning 3-D is refused", "[sun_sensor]") {
  SunSensorParams lonely = coarse(0.0);
  lonely.cell_normals_B.pop_back();  // −z has no partner any more
  CHECK_THROWS_WITH(SunSensorModel(lonely), Catch::Contains("opposite"));
  SunSensorParams flat = coarse(0.0);
  flat.cell_normals_B.resize(4);  // ±x, ±y only
  CHECK_THROWS_WITH(SunSensorModel(flat), Catch::Contains("three dimensions"));
}
