// SPDX-License-Identifier: Apache-2.0
// The thruster sequencer node (seed S1) against a scripted time master that plays the Sun
// sensor: it must subscribe to the angle sensor alone (no rate topic), and a Sun 2 deg
// beyond the upper limit must bring one correction pulse on the couple that lowers the
// angle, its on-time the pulse's, stamped with the step it answers.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <thread>

#include "bus/Convert.hpp"
#include "bus/TimeMaster.hpp"
#include "components/thruster_sequencer/ThrusterSequencerNode.hpp"
#include "tests/support/FedByScript.hpp"
#include "tests/support/TestDomain.hpp"
#include "tests/support/TestUnits.hpp"

namespace {

using namespace flatsat;

constexpr std::uint64_t kSteps = 30;
constexpr double kAngle = 3.0 * kDeg;  // beyond A3 = 1 deg

class ScriptedPeers final : public bus::TimeMaster {
 public:
  ScriptedPeers(bus::Bus& bus, bus::NodeOptions options)
      : TimeMaster(bus, std::move(options), {100'000'000, kSteps - 1}) {}
  std::map<std::uint64_t, msg::ThrusterCmd> received;

 private:
  void publishStep(const bus::StepContext& ctx) override {
    msg::SunSensorReading sun;
    bus::stamp(sun.header(), ctx, "sun_sensor");
    // Body turned by +θ about y sees the Sun at (cos θ, 0, sin θ).
    bus::put(sun.sun_body_unit(), Eigen::Vector3d(std::cos(kAngle), 0.0, std::sin(kAngle)));
    sun.valid(true);
    sun_.write(sun);
  }
  void advance(const bus::StepContext& ctx) override { received[ctx.step] = command_.at(ctx.step); }
  bus::WriterOf<bus::topics::kSunSensor>& sun_ = addOutput(bus::topics::kSunSensor);
  bus::InputOf<bus::topics::kThrusterCmd>& command_ = addInput(bus::topics::kThrusterCmd);
};

sim::ThrusterParams thruster(Eigen::Vector3d r, Eigen::Vector3d d) {
  sim::ThrusterParams t;
  t.r_B_m = r;
  t.direction_B = d;
  t.thrust_N = 1.0;
  return t;
}

}  // namespace

TEST_CASE("thruster sequencer node reads only the Sun sensor and fires the lowering couple",
          "[thruster_sequencer][component][dds]") {
  const std::uint32_t domain = test::testDomain();
  thruster_sequencer::ThrusterSequencerParams node_params;
  auto& params = node_params.angle_only;
  const Eigen::Vector3d up(0, 0, 0.5), down(0, 0, -0.5), x = Eigen::Vector3d::UnitX();
  params.thrusters = {thruster(up, x), thruster(down, -x), thruster(up, -x), thruster(down, x)};
  params.inertia_B_kg_m2 = Eigen::Vector3d(60.0, 180.0 / std::numbers::pi, 70.0).asDiagonal();

  const bus::Schedule node_view = {{"dynamics_server", 1}, {"thruster_sequencer", 1}, {"sun_sensor", 1}};
  const bus::Schedule master_view = {{"dynamics_server", 1}, {"thruster_sequencer", 1}};
  bus::Bus script_bus({domain, bus::NetworkProfile::kLoopback, "script"});
  bus::Bus node_bus({domain, bus::NetworkProfile::kLoopback, "thruster_sequencer"});
  ScriptedPeers script(script_bus, {"dynamics_server", master_view});
  thruster_sequencer::ThrusterSequencerNode node(node_bus, test::fedByScript({"thruster_sequencer", node_view}), node_params);
  CHECK(node.inputTopics() == std::vector<std::string>{std::string(bus::topics::kSunSensor.name)});

  std::thread node_thread([&] { node.run(); });
  script.run();
  node_thread.join();

  REQUIRE(script.received.size() == kSteps);
  for (const auto& [k, cmd] : script.received) {
    CAPTURE(k);
    CHECK(cmd.header().step() == k);
    CHECK(cmd.angle_rad() == Approx(kAngle));
    CHECK(cmd.thruster_count() == 4);
    // Only step 0 fires: the next correction pulse is due T1 = 10 s later.
    const double pulse_s = k == 0 ? params.pulse_on_time_s : 0.0;
    CHECK(cmd.pulse() == (k == 0 ? -1 : 0));
    CHECK(cmd.on_time_s()[0] == 0.0);
    CHECK(cmd.on_time_s()[1] == 0.0);
    CHECK(cmd.on_time_s()[2] == Approx(pulse_s));
    CHECK(cmd.on_time_s()[3] == Approx(pulse_s));
    CHECK(cmd.phase() == static_cast<std::uint8_t>(thruster_sequencer::LimitCyclePhase::kCorrecting));
  }
}
