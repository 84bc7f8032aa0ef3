// SPDX-License-Identifier: Apache-2.0
// The attitude controller node against a scripted time master that plays the
// estimator and the wheel tachometers: it reads those two topics alone, answers
// a Sun 0.02 rad off its pointing axis with the PD law's torque through the
// wheels (τ = kp·θ about x × s, wheel torque −τ on three orthogonal wheels),
// stamped with the step it answers, and commands nothing on an invalid estimate.
#include <catch2/catch.hpp>

#include <cmath>

#include "bus/Convert.hpp"
#include "bus/TimeMaster.hpp"
#include "components/attitude_controller/AttitudeControllerNode.hpp"
#include "tests/support/FedByScript.hpp"
#include "tests/support/NodeUnderTest.hpp"

namespace {

using namespace flatsat;

constexpr std::uint64_t kSteps = 20;
constexpr std::uint64_t kInvalidFrom = 10;  // the estimate is flagged invalid from this step on
constexpr double kOffset_rad = 0.02;       // inside max_rate·kd/kp = 0.05 rad: no rate limit

class ScriptedPeers final : public bus::TimeMaster {
 public:
  ScriptedPeers(bus::Bus& bus, bus::NodeOptions options)
      : TimeMaster(bus, std::move(options), {100'000'000, kSteps - 1}) {}
  std::map<std::uint64_t, msg::WheelTorqueCmd> received;

 private:
  void publishStep(const bus::StepContext& ctx) override {
    msg::AttitudeEstimate estimate;
    bus::stamp(estimate.header(), ctx, "estimator");
    bus::put(estimate.q_inertial_body(), Eigen::Quaterniond::Identity());
    // The Sun turned by the offset about body z from the pointing axis x.
    bus::put(estimate.sun_body_unit(), Eigen::Vector3d(std::cos(kOffset_rad), std::sin(kOffset_rad), 0.0));
    estimate.initialized(true);
    estimate.valid(ctx.step < kInvalidFrom);
    estimate_.write(estimate);
    msg::WheelTachReading tach;
    bus::stamp(tach.header(), ctx, "wheel_tach");
    tach.valid(true);
    tach_.write(tach);
  }
  void advance(const bus::StepContext& ctx) override { received[ctx.step] = command_.at(ctx.step); }
  bus::WriterOf<bus::topics::kAttitudeEstimate>& estimate_ = addOutput(bus::topics::kAttitudeEstimate);
  bus::WriterOf<bus::topics::kWheelTach>& tach_ = addOutput(bus::topics::kWheelTach);
  bus::InputOf<bus::topics::kWheelTorqueCmd>& command_ = addInput(bus::topics::kWheelTorqueCmd);
};

}  // namespace

TEST_CASE("attitude controller node turns the Sun offset into wheel torques, and stops on an invalid estimate",
          "[attitude_controller][component][dds]") {
  attitude_controller::AttitudeControllerNodeParams params;
  auto& law = params.law;  // defaults: kp 0.02 N m/rad, kd 0.2 N m s/rad, 0.01 N m, 0.005 rad/s
  law.wheels.count = 3;    // along body x, y, z
  law.wheels.inertia_kg_m2 = Eigen::Vector4d(0.01, 0.01, 0.01, 0.0);

  const bus::Schedule node_view = {
      {"dynamics_server", 1}, {"attitude_controller", 1}, {"estimator", 1}, {"wheel_tach", 1}};
  const bus::Schedule master_view = {{"dynamics_server", 1}, {"attitude_controller", 1}};
  test::NodeTestBuses buses("attitude_controller");
  ScriptedPeers script(buses.script, {"dynamics_server", master_view});
  attitude_controller::AttitudeControllerNode node(
      buses.node, test::fedByScript({"attitude_controller", node_view}), params);
  CHECK(node.inputTopics() == std::vector<std::string>{std::string(bus::topics::kAttitudeEstimate.name),
                                                       std::string(bus::topics::kWheelTach.name)});

  test::runTogether(script, node);

  REQUIRE(script.received.size() == kSteps);
  const double tau_Nm = law.kp_Nm_per_rad * kOffset_rad;  // about +z (x × s), no rate, no stored momentum
  for (const auto& [k, cmd] : script.received) {
    CAPTURE(k);
    CHECK(cmd.header().step() == k);
    if (k < kInvalidFrom) {
      CHECK(cmd.pointing_error_rad() == Approx(kOffset_rad).epsilon(1e-12));
      CHECK(cmd.tau_body_cmd_Nm()[2] == Approx(tau_Nm).epsilon(1e-12));
      CHECK(cmd.torque_Nm()[2] == Approx(-tau_Nm).epsilon(1e-12));
      CHECK(std::abs(cmd.torque_Nm()[0]) < 1e-18);
      CHECK(std::abs(cmd.torque_Nm()[1]) < 1e-18);
      CHECK_FALSE(cmd.saturated());
    } else {
      for (int i = 0; i < 4; ++i) CHECK(cmd.torque_Nm()[i] == 0.0);
      CHECK(cmd.pointing_error_rad() == 0.0);
    }
  }
}
