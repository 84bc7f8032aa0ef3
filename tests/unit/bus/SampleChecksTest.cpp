// SPDX-License-Identifier: Apache-2.0
// The contract every consumer checks a sample against (bus/SampleChecks.hpp):
// a value that is not finite, wherever it sits in the sample, or outside the
// topic's physical range breaks it, and the missing form of a topic holds no
// measurement, no command and the sample's own header.
#include <catch2/catch.hpp>

#include <cstring>
#include <limits>

#include "bus/SampleChecks.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"

using namespace flatsat;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

template <class Sample>
Sample stamped() {
  Sample s;
  bus::stamp(s.header(), {7, 700'000'000, 100'000'000}, "test");
  return s;
}

}  // namespace

TEST_CASE("a value that is not finite breaks the contract wherever it sits", "[unit][bus][trust]") {
  auto gyro = stamped<msg::GyroReading>();
  gyro.valid(true);
  CHECK_FALSE(bus::breachOf(gyro));
  gyro.w_body_rad_s()[2] = kNaN;
  const auto breach = bus::breachOf(gyro);
  REQUIRE(breach);
  CHECK(std::strcmp(breach.field, "w_body_rad_s") == 0);
  CHECK(std::strcmp(breach.reason, "not finite") == 0);

  auto estimate = stamped<msg::AttitudeEstimate>();
  estimate.q_inertial_body({1.0, 0.0, 0.0, 0.0});
  CHECK_FALSE(bus::breachOf(estimate));
  estimate.attitude_bias_cov_body_rad2_s()[8] = -kInf;  // the last field of the last covariance
  REQUIRE(bus::breachOf(estimate));
  CHECK(std::strcmp(bus::breachOf(estimate).field, "attitude_bias_cov_body_rad2_s") == 0);

  auto truth = stamped<msg::TruthState>();
  truth.q_inertial_body({1.0, 0.0, 0.0, 0.0});
  CHECK_FALSE(bus::breachOf(truth));
  truth.thruster_impulse_total_Ns()[11] = kNaN;  // the last double field of the type
  CHECK(bus::breachOf(truth));
}

TEST_CASE("values outside a topic's physical range break it, commands only when not finite",
          "[unit][bus][trust]") {
  auto magnetometer = stamped<msg::MagnetometerReading>();
  magnetometer.b_body_T({3e-5, -2e-5, 4e-5});  // a field of low orbit
  magnetometer.valid(true);
  CHECK_FALSE(bus::breachOf(magnetometer));
  magnetometer.b_body_T()[0] = 30.0;  // 30 µT sent in microtesla: a unit error
  CHECK(bus::breachOf(magnetometer));

  auto sun = stamped<msg::SunSensorReading>();
  sun.sun_body_unit({0.6, 0.0, 0.8});
  sun.valid(true);
  CHECK_FALSE(bus::breachOf(sun));
  sun.sun_body_unit({0.6, 0.0, 0.9});  // |v| = 1.08: not a direction
  CHECK(bus::breachOf(sun));
  sun.valid(false);
  sun.sun_body_unit({0.0, 0.0, 0.0});  // an invalid reading is zero
  CHECK_FALSE(bus::breachOf(sun));
  sun.cell_count(13);
  CHECK(bus::breachOf(sun));

  auto gyro = stamped<msg::GyroReading>();
  gyro.w_body_rad_s({0.0, bus::kMaxBodyRateRadS, 0.0});
  CHECK_FALSE(bus::breachOf(gyro));
  gyro.w_body_rad_s()[1] = -1e300;
  CHECK(bus::breachOf(gyro));

  auto wheels = stamped<msg::WheelTorqueCmd>();
  wheels.torque_Nm({1e300, -1e300, 0.0, 0.0});  // held to the motor limit by the dynamics server
  CHECK_FALSE(bus::breachOf(wheels));
  wheels.torque_Nm()[3] = kNaN;
  CHECK(bus::breachOf(wheels));

  auto thrusters = stamped<msg::ThrusterCmd>();
  thrusters.thruster_count(12);
  CHECK_FALSE(bus::breachOf(thrusters));
  thrusters.on_time_s()[0] = -0.1;
  CHECK(bus::breachOf(thrusters));

  auto grant = stamped<msg::StepGrant>();
  grant.step_period_ns(0);
  CHECK(bus::breachOf(grant));
}

TEST_CASE("the missing form keeps the header and holds nothing to act on", "[unit][bus][trust]") {
  auto gyro = stamped<msg::GyroReading>();
  gyro.w_body_rad_s({kNaN, 1.0, 2.0});
  gyro.valid(true);
  REQUIRE(bus::takeAsMissing(gyro));
  CHECK(gyro.header().step() == 7);
  CHECK(bus::text(gyro.header().source()) == "test");
  CHECK_FALSE(gyro.valid());
  CHECK(gyro.w_body_rad_s() == std::array<double, 3>{0.0, 0.0, 0.0});
  CHECK_FALSE(bus::breachOf(gyro));

  auto estimate = stamped<msg::AttitudeEstimate>();
  estimate.valid(true);
  estimate.initialized(true);
  estimate.w_body_rad_s({kNaN, 0.0, 0.0});
  REQUIRE(bus::takeAsMissing(estimate));
  CHECK_FALSE(estimate.valid());
  CHECK(estimate.q_inertial_body() == std::array<double, 4>{1.0, 0.0, 0.0, 0.0});
  CHECK_FALSE(bus::breachOf(estimate));

  auto dipole = stamped<msg::DipoleCmd>();
  dipole.m_body_Am2({kNaN, 5.0, 5.0});
  dipole.active(true);
  REQUIRE(bus::takeAsMissing(dipole));
  CHECK(dipole.m_body_Am2() == std::array<double, 3>{0.0, 0.0, 0.0});
  CHECK_FALSE(dipole.active());
  CHECK(dipole.header().step() == 7);

  auto flaps = stamped<msg::FlapCmd>();
  REQUIRE(bus::takeAsMissing(flaps));
  CHECK(flaps.split() == 255);  // neutral

  // The truth and the protocol have no missing form: dropped, never made up.
  auto truth = stamped<msg::TruthState>();
  CHECK_FALSE(bus::takeAsMissing(truth));
  auto grant = stamped<msg::StepGrant>();
  CHECK_FALSE(bus::takeAsMissing(grant));
}
