// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <limits>
#include <stdexcept>

#include <catch2/catch.hpp>

#include "components/magnetometer/MagnetometerModel.hpp"
#include "tests/unit/components/SampleStats.hpp"

using flatsat::magnetometer::MagnetometerModel;
using flatsat::magnetometer::MagnetometerParams;
using flatsat::test::checkGaussian;
using flatsat::test::SampleStats;

namespace {

MagnetometerParams noiseFree() {
  MagnetometerParams p;
  p.noise_T = 0.0;
  return p;
}

const Eigen::Vector3d kFieldLeo_B_T(2.1e-5, -3.4e-5, 1.7e-5);  // typical LEO field, body axes

}  // namespace

TEST_CASE("Magnetometer applies scale factor and bias", "[components][magnetometer]") {
  GIVEN("a noise-free sensor with a bias and per-axis gains") {
    MagnetometerParams p = noiseFree();
    p.bias_B_T = Eigen::Vector3d(1e-7, -2e-7, 3e-7);
    p.scale_factor = Eigen::Vector3d(1.01, 0.98, 1.0);
    MagnetometerModel mag(p);
    WHEN("it measures a field within range") {
      const auto out = mag.step({kFieldLeo_B_T}, 0);
      THEN("the output is scale ⊙ b + bias, unsaturated") {
        const Eigen::Vector3d expected(1.01 * 2.1e-5 + 1e-7, 0.98 * -3.4e-5 - 2e-7, 1.7e-5 + 3e-7);
        CHECK((out.b_B_T - expected).norm() < 1e-18);
        CHECK_FALSE(out.saturated);
      }
    }
  }
}

TEST_CASE("Magnetometer noise is zero-mean Gaussian with the set sigma", "[components][magnetometer]") {
  MagnetometerParams p;
  p.noise_T = 2e-7;
  p.bias_B_T = Eigen::Vector3d(5e-7, 0.0, -5e-7);
  MagnetometerModel mag(p);
  SampleStats stats[3];
  for (int k = 0; k < 20000; ++k) {
    const auto out = mag.step({kFieldLeo_B_T}, k * 100'000'000LL);
    for (int i = 0; i < 3; ++i) {
      stats[i].add(out.b_B_T[i]);
    }
  }
  for (int i = 0; i < 3; ++i) {
    checkGaussian(stats[i], kFieldLeo_B_T[i] + p.bias_B_T[i], p.noise_T);
  }
}

TEST_CASE("Magnetometer noise replays from the seed", "[components][magnetometer]") {
  MagnetometerParams p;
  p.seed = 42;
  MagnetometerModel a(p);
  MagnetometerModel b(p);
  p.seed = 43;
  MagnetometerModel other(p);
  Eigen::Vector3d first[10];
  bool differs = false;
  for (int k = 0; k < 10; ++k) {
    first[k] = a.step({kFieldLeo_B_T}, k).b_B_T;
    CHECK(first[k] == b.step({kFieldLeo_B_T}, k).b_B_T);
    differs = differs || first[k] != other.step({kFieldLeo_B_T}, k).b_B_T;
  }
  CHECK(differs);
  a.reset();
  for (int k = 0; k < 10; ++k) {
    CHECK(a.step({kFieldLeo_B_T}, k).b_B_T == first[k]);
  }
}

TEST_CASE("Magnetometer quantises to the ADC step", "[components][magnetometer]") {
  MagnetometerParams p = noiseFree();
  p.quantum_T = 5e-8;
  MagnetometerModel mag(p);
  const auto out = mag.step({kFieldLeo_B_T + Eigen::Vector3d(1.3e-8, -2.6e-8, 2.4e-8)}, 0);
  for (int i = 0; i < 3; ++i) {
    const double steps = out.b_B_T[i] / p.quantum_T;
    CHECK(std::abs(steps - std::round(steps)) < 1e-9);
  }
  // Nearest multiples of 50 nT, worked by hand: 21.013 → 21.00, −34.026 → −34.05, 17.024 → 17.00 µT.
  CHECK((out.b_B_T - Eigen::Vector3d(2.100e-5, -3.405e-5, 1.700e-5)).norm() < 1e-15);
}

TEST_CASE("Magnetometer saturates each axis at the range", "[components][magnetometer]") {
  GIVEN("a ±50 µT sensor") {
    MagnetometerParams p = noiseFree();
    p.range_T = 5e-5;
    MagnetometerModel mag(p);
    WHEN("one axis exceeds the range on each side") {
      const auto out = mag.step({Eigen::Vector3d(7e-5, -9e-5, 1e-5)}, 0);
      THEN("those axes clip, the third passes and the flag is set") {
        CHECK(out.b_B_T == Eigen::Vector3d(5e-5, -5e-5, 1e-5));
        CHECK(out.saturated);
      }
    }
    WHEN("the field is inside the range") {
      THEN("nothing is flagged") { CHECK_FALSE(mag.step({Eigen::Vector3d(4e-5, -4e-5, 0.0)}, 0).saturated); }
    }
  }
}

TEST_CASE("Magnetometer params reject bad values", "[components][magnetometer]") {
  CHECK(MagnetometerParams{}.validate().empty());
  MagnetometerParams p;
  p.noise_T = -1e-9;
  p.bias_B_T.x() = std::numeric_limits<double>::quiet_NaN();
  p.scale_factor.y() = 0.0;
  p.quantum_T = -1.0;
  p.range_T = 0.0;
  const auto errors = p.validate();
  REQUIRE(errors.size() == 5);
  CHECK(errors[0].rfind("noise_T:", 0) == 0);
  CHECK(errors[1].rfind("bias_B_T:", 0) == 0);
  CHECK(errors[2].rfind("scale_factor:", 0) == 0);
  CHECK(errors[3].rfind("quantum_T:", 0) == 0);
  CHECK(errors[4].rfind("range_T:", 0) == 0);
  CHECK_THROWS_WITH(MagnetometerModel(p), Catch::Matchers::Contains("range_T: must be finite and > 0"));
}
