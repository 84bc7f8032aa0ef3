// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <catch2/catch.hpp>

#include "components/star_tracker/StarTrackerModel.hpp"
#include "tests/support/TestUnits.hpp"
#include "tests/unit/components/SampleStats.hpp"

using flatsat::star_tracker::applyError;
using flatsat::star_tracker::StarTrackerInput;
using flatsat::star_tracker::StarTrackerModel;
using flatsat::star_tracker::StarTrackerParams;
using flatsat::test::checkGaussian;
using flatsat::test::SampleStats;

namespace {

constexpr double kArcsec = kDeg / 3600.0;

/// Inertial attitude with the boresight (body +z, identity mounting) 90° from nadir and the
/// Sun along body +x: a star tracker's best case.
StarTrackerInput clearSky() {
  StarTrackerInput in;
  in.q_NB = Eigen::Quaterniond::Identity();
  in.r_N_m = Eigen::Vector3d(6938.0e3, 0.0, 0.0);  // 560 km: nadir is -x, the boresight +z
  in.sun_B_unit = Eigen::Vector3d::UnitX();
  return in;
}

/// [rad] rotation vector taking the true attitude to the measured one, body axes.
Eigen::Vector3d errorOf(const Eigen::Quaterniond& measured, const Eigen::Quaterniond& truth) {
  const Eigen::AngleAxisd aa(truth.conjugate() * measured);
  return aa.angle() * aa.axis();
}

}  // namespace

TEST_CASE("star tracker noise is the datasheet's across and about the boresight", "[star_tracker]") {
  StarTrackerParams p;
  p.noise_cross_rad = 4 * kArcsec;
  p.noise_about_rad = 30 * kArcsec;
  // Boresight along body +y: sensor z -> body y, so "about" shows on body y.
  p.q_body_sensor = Eigen::Quaterniond(Eigen::AngleAxisd(-std::numbers::pi / 2, Eigen::Vector3d::UnitX()));
  StarTrackerModel model(p);
  StarTrackerInput in = clearSky();
  const Eigen::Quaterniond truth(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  in.q_NB = truth;
  in.r_N_m = truth * Eigen::Vector3d(0.0, 0.0, 6938.0e3);  // nadir body -z: the boresight is 90° from it
  SampleStats x, y, z;
  for (int i = 0; i < 20000; ++i) {
    const auto out = model.step(in, i);
    REQUIRE(out.valid);
    const Eigen::Vector3d e = errorOf(applyError(out.q_NB_true, out.error_B_rad), truth);
    x.add(e.x());
    y.add(e.y());
    z.add(e.z());
  }
  checkGaussian(x, 0.0, p.noise_cross_rad);
  checkGaussian(y, 0.0, p.noise_about_rad);
  checkGaussian(z, 0.0, p.noise_cross_rad);
}

TEST_CASE("star tracker gives no solution when spinning, dazzled or looking at the Earth", "[star_tracker]") {
  StarTrackerParams p;
  p.max_rate_rad_s = 2 * kDeg;
  p.sun_exclusion_rad = 35 * kDeg;
  p.earth_exclusion_rad = 20 * kDeg;
  StarTrackerModel model(p);
  CHECK(model.step(clearSky(), 0).valid);

  auto in = clearSky();
  in.w_B_rad_s = Eigen::Vector3d(0.0, 2.1 * kDeg, 0.0);
  CHECK_FALSE(model.step(in, 0).valid);

  // Sun 34° / 36° from the boresight; in umbra there is no Sun to exclude.
  in = clearSky();
  in.sun_B_unit = Eigen::Vector3d(std::sin(34 * kDeg), 0.0, std::cos(34 * kDeg));
  CHECK_FALSE(model.step(in, 0).valid);
  in.illumination = 0.0;
  CHECK(model.step(in, 0).valid);
  in = clearSky();
  in.sun_B_unit = Eigen::Vector3d(std::sin(36 * kDeg), 0.0, std::cos(36 * kDeg));
  CHECK(model.step(in, 0).valid);

  // At 560 km the Earth's limb is asin(R/r) = 66.8° from nadir: the boresight must stay
  // 86.8° from nadir. Tilt the boresight towards nadir (-x) by 2° and by 4°.
  const double limb = std::asin(6378137.0 / 6938.0e3);
  REQUIRE(limb / kDeg == Approx(66.82).margin(0.01));
  in = clearSky();
  in.q_NB = Eigen::Quaterniond(Eigen::AngleAxisd(-2 * kDeg, Eigen::Vector3d::UnitY()));
  CHECK(model.step(in, 0).valid);  // 88° from nadir
  in.q_NB = Eigen::Quaterniond(Eigen::AngleAxisd(-4 * kDeg, Eigen::Vector3d::UnitY()));
  CHECK_FALSE(model.step(in, 0).valid);  // 86°
}

TEST_CASE("star tracker error follows the MEKF's convention q_meas = q (x) exp(e/2)", "[star_tracker]") {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(1.0, Eigen::Vector3d(0, 1, 1).normalized()));
  const Eigen::Vector3d e(1e-4, -2e-4, 3e-4);
  const Eigen::Quaterniond measured = applyError(q, e);
  // First order: q_meas ≈ q ⊗ (1, e/2).
  const Eigen::Quaterniond first_order = q * Eigen::Quaterniond(1.0, e.x() / 2, e.y() / 2, e.z() / 2);
  CHECK(measured.angularDistance(first_order.normalized()) < 1e-10);
  CHECK((errorOf(measured, q) - e).norm() < 1e-15);
}

TEST_CASE("star tracker parameters are checked", "[star_tracker]") {
  StarTrackerParams p;
  p.max_rate_rad_s = 0.0;
  p.sun_exclusion_rad = 4.0;
  CHECK(p.validate().size() == 2);
  CHECK_THROWS_AS(StarTrackerModel(p), std::invalid_argument);
}

TEST_CASE("star tracker on a mounting known wrongly reports the attitude rotated by the error", "[star_tracker]") {
  // Mounted with identity, believed turned 0.1 deg about body x: the unit's
  // q_NS, turned into body axes on the believed mounting, is the truth
  // rotated by q_BS ⊗ q_BS_onboard⁻¹ = 0.1 deg about −x (noise off).
  StarTrackerParams p;
  p.noise_cross_rad = p.noise_about_rad = 0.0;
  const double error_rad = 0.1 * kDeg;
  p.q_body_sensor_onboard = Eigen::Quaterniond(Eigen::AngleAxisd(error_rad, Eigen::Vector3d::UnitX()));
  StarTrackerModel model(p);
  const auto out = model.step(clearSky(), 0);
  REQUIRE(out.valid);
  const Eigen::Vector3d e = errorOf(applyError(out.q_NB_true, out.error_B_rad), out.q_NB_true);
  CHECK(e.x() == Approx(-error_rad).epsilon(1e-12));
  CHECK(std::abs(e.y()) < 1e-15);
  CHECK(std::abs(e.z()) < 1e-15);

  // Believed exactly as mounted: the error is the noise alone, sample for sample.
  StarTrackerParams known = p;
  known.noise_cross_rad = 4 * kArcsec;
  known.q_body_sensor_onboard = known.q_body_sensor;
  StarTrackerParams plain = known;
  plain.q_body_sensor_onboard.reset();
  StarTrackerModel a(known), b(plain);
  for (int i = 0; i < 10; ++i) CHECK(a.step(clearSky(), i).error_B_rad == b.step(clearSky(), i).error_B_rad);
}
