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

TEST_CASE("Magnetometer misalignment turns the field into the sensor's axes", "[components][magnetometer]") {
  // Sensor axes turned by +10° about body z: a body-x field shows at -10° in
  // the sensor's x-y plane (a passive rotation), with its magnitude kept.
  MagnetometerParams p = noiseFree();
  const double angle = 10.0 * M_PI / 180.0;
  p.misalignment_rad = Eigen::Vector3d(0.0, 0.0, angle);
  MagnetometerModel mag(p);
  const double b = 3.0e-5;
  const auto out = mag.step({Eigen::Vector3d(b, 0.0, 0.0)}, 0);
  CHECK(out.b_B_T.x() == Approx(b * std::cos(angle)).epsilon(1e-12));
  CHECK(out.b_B_T.y() == Approx(-b * std::sin(angle)).epsilon(1e-12));
  CHECK(std::abs(out.b_B_T.z()) < 1e-20);
  const auto general = mag.step({kFieldLeo_B_T}, 0);
  CHECK(general.b_B_T.norm() == Approx(kFieldLeo_B_T.norm()).epsilon(1e-12));
  CHECK(general.b_B_T.z() == Approx(kFieldLeo_B_T.z()).epsilon(1e-12));  // the rotation axis
}

TEST_CASE("Magnetometer sees the torquers' own field and can blank it", "[components][magnetometer]") {
  MagnetometerParams p = noiseFree();
  // 50 nT per A m² on the coil's own axis, 5 nT across: a compact bus.
  p.coil_coupling_T_per_Am2 = Eigen::Matrix3d::Constant(5e-9);
  p.coil_coupling_T_per_Am2.diagonal().setConstant(5e-8);
  const Eigen::Vector3d m(10.0, 0.0, -4.0);
  SECTION("unblanked, the coupling adds C m to the reading") {
    MagnetometerModel mag(p);
    const auto on = mag.step({kFieldLeo_B_T, m}, 0);
    const Eigen::Vector3d expected = kFieldLeo_B_T + Eigen::Vector3d(5e-7 - 2e-8, 5e-8 - 2e-8, 5e-8 - 2e-7);
    CHECK((on.b_B_T - expected).norm() < 1e-18);
    CHECK_FALSE(on.blanked);
    CHECK((mag.step({kFieldLeo_B_T, Eigen::Vector3d::Zero()}, 1).b_B_T - kFieldLeo_B_T).norm() < 1e-18);
  }
  SECTION("blanking marks every sample taken with a coil on, and only those") {
    p.blank_while_coils_on = true;
    MagnetometerModel mag(p);
    CHECK(mag.step({kFieldLeo_B_T, m}, 0).blanked);
    CHECK(mag.step({kFieldLeo_B_T, Eigen::Vector3d(0.0, 1e-3, 0.0)}, 1).blanked);
    const auto quiet = mag.step({kFieldLeo_B_T, Eigen::Vector3d::Zero()}, 2);
    CHECK_FALSE(quiet.blanked);
    CHECK((quiet.b_B_T - kFieldLeo_B_T).norm() < 1e-18);
  }
}

TEST_CASE("Magnetometer params reject a half-turn misalignment and a non-finite coupling", "[components][magnetometer]") {
  MagnetometerParams p;
  p.misalignment_rad = Eigen::Vector3d(0.0, M_PI, 0.0);
  p.coil_coupling_T_per_Am2(1, 2) = std::numeric_limits<double>::quiet_NaN();
  const auto errors = p.validate();
  const auto has = [&](const std::string& prefix) {
    for (const auto& e : errors) {
      if (e.rfind(prefix, 0) == 0) return true;
    }
    return false;
  };
  CHECK(has("misalignment_rad: "));
  CHECK(has("coil_coupling_T_per_Am2: "));
  p = MagnetometerParams{};
  p.misalignment_rad = Eigen::Vector3d(0.01, -0.02, 0.005);
  CHECK(p.validate().empty());
}
