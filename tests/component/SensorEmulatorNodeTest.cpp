// SPDX-License-Identifier: Apache-2.0
// Each sensor emulator node against a scripted time master that publishes the
// truth: with its noise, bias and misalignment off, every reading is the truth
// it was stamped with (the step's, not a neighbour's), taken from the right
// fields; a scenario fault acts on its channel from its start on.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>

#include "bus/Convert.hpp"
#include "bus/TimeMaster.hpp"
#include "components/gyro/GyroNode.hpp"
#include "components/magnetometer/MagnetometerNode.hpp"
#include "components/star_tracker/StarTrackerNode.hpp"
#include "components/sun_sensor/SunSensorNode.hpp"
#include "components/wheel_tach/WheelTachNode.hpp"
#include "sim/PanelModel.hpp"
#include "tests/support/FedByScript.hpp"
#include "tests/support/NodeUnderTest.hpp"

namespace {

using namespace flatsat;

constexpr std::uint64_t kSteps = 20;

/// The truth at step k: every field an emulator reads changes from step to step.
msg::TruthState truthAt(std::uint64_t step) {
  const double k = static_cast<double>(step);
  msg::TruthState t;
  bus::put(t.q_inertial_body(), Eigen::Quaterniond(Eigen::AngleAxisd(1e-3 * k, Eigen::Vector3d::UnitZ())));
  bus::put(t.w_body_rad_s(), Eigen::Vector3d(1e-3 * k, -2e-3, 5e-4));
  bus::put(t.b_body_T(), Eigen::Vector3d(2e-5, -1e-5 + 1e-7 * k, 3e-5));
  bus::put(t.sun_body_unit(), Eigen::Vector3d(std::cos(0.01 * k), std::sin(0.01 * k), 0.0));
  t.illumination(1.0);
  t.solar_flux_W_m2(sim::kSolarFlux1Au_W_m2);
  // Nadir along −x: the star tracker's boresight (+z) sits 24 deg above the limb.
  bus::put(t.r_inertial_m(), Eigen::Vector3d(7.0e6, 0.0, 0.0));
  t.wheel_count(4);
  bus::put(t.wheel_speed_rad_s(), Eigen::Vector4d(10.0 * k, -5.0, 3.0, 0.0));
  return t;
}

template <const auto& Topic>
class TruthScript final : public bus::TimeMaster {
 public:
  TruthScript(bus::Bus& bus, bus::NodeOptions options)
      : TimeMaster(bus, std::move(options), {100'000'000, kSteps - 1}) {}
  std::map<std::uint64_t, typename std::remove_cvref_t<decltype(Topic)>::Type> received;

 private:
  void publishStep(const bus::StepContext& ctx) override {
    auto truth = truthAt(ctx.step);
    bus::stamp(truth.header(), ctx, "dynamics_server");
    truth_.write(truth);
  }
  void advance(const bus::StepContext& ctx) override { received[ctx.step] = reading_.at(ctx.step); }
  bus::WriterOf<bus::topics::kTruth>& truth_ = addOutput(bus::topics::kTruth);
  bus::InputOf<Topic>& reading_ = addInput(Topic);
};

/// The readings of emulator `name` (a Node built with `params`), by step.
template <class Node, const auto& Topic>
auto emulate(const std::string& name, const typename Node::Params& params) {
  const bus::Schedule view = {{"dynamics_server", 1}, {name, 1}};
  test::NodeTestBuses buses(name);
  TruthScript<Topic> script(buses.script, {"dynamics_server", view});
  Node node(buses.node, test::fedByScript({name, view}), params);
  test::runTogether(script, node);
  REQUIRE(script.received.size() == kSteps);
  return script.received;
}

}  // namespace

TEST_CASE("gyro node reports the true rate of its step, and a scenario bias from its start on",
          "[gyro][component][dds]") {
  gyro::GyroNode::Params params;
  params.model.angle_random_walk_rad_per_sqrt_s = params.model.rate_random_walk_rad_per_s_sqrt_s = 0.0;
  SensorFault bias;
  bias.kind = SensorFaultKind::kBias;
  bias.channel = 1;
  bias.magnitude = 0.01;
  bias.start_ns = 1'000'000'000;  // step 10
  params.faults = {bias};
  for (const auto& [k, reading] : emulate<gyro::GyroNode, bus::topics::kGyro>("gyro", params)) {
    CAPTURE(k);
    CHECK(reading.header().step() == k);
    CHECK(reading.valid());
    const Eigen::Vector3d expected = bus::vec3(truthAt(k).w_body_rad_s()) + Eigen::Vector3d(0, k >= 10 ? 0.01 : 0.0, 0);
    CHECK((bus::vec3(reading.w_body_rad_s()) - expected).norm() < 1e-15);
  }
}

TEST_CASE("magnetometer node reports the true field of its step", "[magnetometer][component][dds]") {
  magnetometer::MagnetometerNode::Params params;
  params.model.noise_T = 0.0;
  for (const auto& [k, reading] :
       emulate<magnetometer::MagnetometerNode, bus::topics::kMagnetometer>("magnetometer", params)) {
    CAPTURE(k);
    CHECK(reading.header().step() == k);
    CHECK(reading.valid());
    CHECK_FALSE(reading.saturated());
    CHECK((bus::vec3(reading.b_body_T()) - bus::vec3(truthAt(k).b_body_T())).norm() < 1e-18);
  }
}

TEST_CASE("Sun sensor node reports the true Sun of its step", "[sun_sensor][component][dds]") {
  sun_sensor::SunSensorNode::Params params;
  params.model.noise_rad = 0.0;
  for (const auto& [k, reading] : emulate<sun_sensor::SunSensorNode, bus::topics::kSunSensor>("sun_sensor", params)) {
    CAPTURE(k);
    CHECK(reading.header().step() == k);
    CHECK(reading.valid());
    CHECK((bus::vec3(reading.sun_body_unit()) - bus::vec3(truthAt(k).sun_body_unit())).norm() < 1e-14);
  }
}

TEST_CASE("wheel tachometer node reports the true speeds of its step", "[wheel_tach][component][dds]") {
  wheel_tach::WheelTachNode::Params params;
  params.model.noise_rad_s = 0.0;
  params.model.wheel_count = 4;
  for (const auto& [k, reading] : emulate<wheel_tach::WheelTachNode, bus::topics::kWheelTach>("wheel_tach", params)) {
    CAPTURE(k);
    CHECK(reading.header().step() == k);
    CHECK(reading.valid());
    CHECK(bus::vec4(reading.wheel_speed_rad_s()) == bus::vec4(truthAt(k).wheel_speed_rad_s()));
  }
}

TEST_CASE("star tracker node reports the true attitude of its step", "[star_tracker][component][dds]") {
  star_tracker::StarTrackerNode::Params params;
  params.model.noise_cross_rad = params.model.noise_about_rad = 0.0;
  for (const auto& [k, reading] :
       emulate<star_tracker::StarTrackerNode, bus::topics::kStarTracker>("star_tracker", params)) {
    CAPTURE(k);
    CHECK(reading.header().step() == k);
    CHECK(reading.valid());
    CHECK(bus::quat(reading.q_inertial_body()).angularDistance(bus::quat(truthAt(k).q_inertial_body())) < 1e-12);
  }
}
