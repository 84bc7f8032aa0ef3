// SPDX-License-Identifier: Apache-2.0
// The estimator node (Mahony) against a scripted time master that plays the
// gyro, the Sun sensor and the magnetometer of a spacecraft held at a chosen
// attitude: each sensor reports the onboard reference direction turned into
// body axes by that attitude. The node must read exactly those three topics,
// acquire the attitude from its first step (TRIAD) and hold it, publish a valid
// estimate stamped with the step it answers, and ride through a Sun sensor
// dropout on the field alone.
#include <catch2/catch.hpp>


#include "bus/Convert.hpp"
#include "bus/TimeMaster.hpp"
#include "components/estimator/EstimatorNode.hpp"
#include "tests/support/FedByScript.hpp"
#include "tests/support/NodeUnderTest.hpp"

namespace {

using namespace flatsat;

constexpr std::uint64_t kSteps = 40;
constexpr std::uint64_t kSunLostFrom = 20;  // the Sun sensor reports no Sun from this step on

/// The attitude the script holds the spacecraft at: 30 deg about (1, 2, 3).
Eigen::Quaterniond trueAttitude() {
  return Eigen::Quaterniond(Eigen::AngleAxisd(30.0 * M_PI / 180.0, Eigen::Vector3d(1, 2, 3).normalized()));
}

class ScriptedPeers final : public bus::TimeMaster {
 public:
  ScriptedPeers(bus::Bus& bus, bus::NodeOptions options, const onboard::ReferenceModelParams& reference)
      : TimeMaster(bus, std::move(options), {100'000'000, kSteps - 1}), reference_(reference) {}
  std::map<std::uint64_t, msg::AttitudeEstimate> received;

 private:
  void publishStep(const bus::StepContext& ctx) override {
    const onboard::ReferenceVectors ref = reference_.step(ctx.sim_time_ns);
    const Eigen::Quaterniond q_NB = trueAttitude();
    msg::GyroReading gyro;
    bus::stamp(gyro.header(), ctx, "gyro");
    gyro.valid(true);  // held: zero rate
    gyro_.write(gyro);
    msg::SunSensorReading sun;
    bus::stamp(sun.header(), ctx, "sun_sensor");
    sun.valid(ctx.step < kSunLostFrom);
    if (sun.valid()) bus::put(sun.sun_body_unit(), q_NB.conjugate() * ref.sun_N_unit);
    sun_.write(sun);
    msg::MagnetometerReading field;
    bus::stamp(field.header(), ctx, "magnetometer");
    bus::put(field.b_body_T(), q_NB.conjugate() * ref.b_N_T);
    field.valid(true);
    magnetometer_.write(field);
  }
  void advance(const bus::StepContext& ctx) override { received[ctx.step] = estimate_.at(ctx.step); }

  onboard::ReferenceModel reference_;
  bus::WriterOf<bus::topics::kGyro>& gyro_ = addOutput(bus::topics::kGyro);
  bus::WriterOf<bus::topics::kSunSensor>& sun_ = addOutput(bus::topics::kSunSensor);
  bus::WriterOf<bus::topics::kMagnetometer>& magnetometer_ = addOutput(bus::topics::kMagnetometer);
  bus::InputOf<bus::topics::kAttitudeEstimate>& estimate_ = addInput(bus::topics::kAttitudeEstimate);
};

}  // namespace

TEST_CASE("estimator node acquires and holds the attitude its sensors agree on, and rides through a Sun dropout",
          "[estimator][component][dds]") {
  estimator::EstimatorNodeParams params;  // Mahony; the onboard model: the default orbit and tilted dipole
  params.reference.orbit.inclination_rad = 1.0;
  params.filter.use_magnetometer = true;

  const bus::Schedule node_view = {{"dynamics_server", 1}, {"estimator", 1}, {"gyro", 1},
                                   {"sun_sensor", 1},      {"magnetometer", 1}};
  const bus::Schedule master_view = {{"dynamics_server", 1}, {"estimator", 1}};
  test::NodeTestBuses buses("estimator");
  ScriptedPeers script(buses.script, {"dynamics_server", master_view}, params.reference);
  estimator::EstimatorNode node(buses.node, test::fedByScript({"estimator", node_view}), params);
  CHECK(node.inputTopics() == std::vector<std::string>{std::string(bus::topics::kGyro.name),
                                                       std::string(bus::topics::kSunSensor.name),
                                                       std::string(bus::topics::kMagnetometer.name)});

  test::runTogether(script, node);

  REQUIRE(script.received.size() == kSteps);
  for (const auto& [k, estimate] : script.received) {
    CAPTURE(k);
    CHECK(estimate.header().step() == k);
    CHECK(estimate.valid());
    CHECK(estimate.sun_used() == (k < kSunLostFrom));
    CHECK(bus::quat(estimate.q_inertial_body()).angularDistance(trueAttitude()) < 1e-9);
    CHECK(bus::vec3(estimate.w_body_rad_s()).norm() < 1e-12);
  }
}
