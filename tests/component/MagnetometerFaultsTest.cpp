// SPDX-License-Identifier: Apache-2.0
// The magnetometer emulator against a scripted time master over real DDS:
// faults from the scenario and from the FaultCmd topic change the published
// readings exactly as specified, and each start and end is published as a
// FaultEvent stamped with its step.
#include <catch2/catch.hpp>

#include <mutex>
#include <thread>

#include "bus/Convert.hpp"
#include "bus/TimeMaster.hpp"
#include "components/magnetometer/MagnetometerNode.hpp"
#include "tests/support/FedByScript.hpp"
#include "tests/support/TestDomain.hpp"

namespace {

using namespace flatsat;

constexpr std::uint64_t kSteps = 50;
constexpr std::int64_t kPeriodNs = 100'000'000;
constexpr double kBias = 1e-6;  // [T] commanded over the bus

Eigen::Vector3d fieldAt(std::uint64_t k) {
  return Eigen::Vector3d(2e-5 + 1e-7 * k, -1e-5, 3e-5 - 2e-7 * k);
}

class Script final : public bus::TimeMaster {
 public:
  Script(bus::Bus& bus, bus::NodeOptions options)
      : TimeMaster(bus, std::move(options), {kPeriodNs, kSteps - 1}),
        events_reader_(bus, bus::topics::kFaultEvent, [this](const msg::FaultEvent& e) {
          std::lock_guard lock(events_mutex_);
          events.push_back(e);
        }) {}
  std::map<std::uint64_t, msg::MagnetometerReading> readings;
  std::mutex events_mutex_;
  std::vector<msg::FaultEvent> events;

 private:
  void publishStep(const bus::StepContext& ctx) override {
    msg::TruthState truth;
    bus::stamp(truth.header(), ctx, "dynamics_server");
    truth.q_inertial_body({1.0, 0.0, 0.0, 0.0});  // a truth's attitude is a unit quaternion (bus/SampleChecks)
    bus::put(truth.b_body_T(), fieldAt(ctx.step));
    truth_.write(truth);
    if (ctx.step == 5) {  // a bias on x over steps 10..14, commanded on the bus
      msg::FaultCmd command;
      bus::stamp(command.header(), ctx, "test");
      bus::setText(command.target(), "magnetometer");
      bus::setText(command.kind(), "bias");
      command.channel(0);
      command.magnitude(kBias);
      command.start_ns(10 * kPeriodNs);
      command.duration_ns(5 * kPeriodNs);
      faults_.write(command);
    }
  }
  void advance(const bus::StepContext& ctx) override { readings[ctx.step] = reading_.at(ctx.step); }

  bus::WriterOf<bus::topics::kTruth>& truth_ = addOutput(bus::topics::kTruth);
  bus::WriterOf<bus::topics::kFaultCmd>& faults_ = addOutput(bus::topics::kFaultCmd);
  bus::InputOf<bus::topics::kMagnetometer>& reading_ = addInput(bus::topics::kMagnetometer);
  bus::ReaderOf<bus::topics::kFaultEvent> events_reader_;
};

SensorFault scenarioFault(SensorFaultKind kind, std::uint64_t first, std::uint64_t steps) {
  return {kind, -1, 0.0, static_cast<std::int64_t>(first) * kPeriodNs,
          static_cast<std::int64_t>(steps) * kPeriodNs};
}

}  // namespace

TEST_CASE("magnetometer faults from the scenario and the bus act on the readings",
          "[magnetometer][component][dds][faults]") {
  const std::uint32_t domain = test::testDomain();
  magnetometer::MagnetometerNode::Params params;
  params.model.noise_T = 0.0;  // readings equal the truth unless a fault acts
  params.faults = {scenarioFault(SensorFaultKind::kDropout, 30, 3),
                   scenarioFault(SensorFaultKind::kStuck, 40, 5)};
  const bus::Schedule schedule = {{"dynamics_server", 1}, {"magnetometer", 1}};

  bus::Bus script_bus({domain, bus::NetworkProfile::kLoopback, "script"});
  bus::Bus node_bus({domain, bus::NetworkProfile::kLoopback, "magnetometer"});
  Script script(script_bus, {"dynamics_server", schedule});
  magnetometer::MagnetometerNode node(node_bus, test::fedByScript({"magnetometer", schedule}), params);
  std::thread node_thread([&] { node.run(); });
  script.run();
  node_thread.join();

  REQUIRE(script.readings.size() == kSteps);
  for (const auto& [k, reading] : script.readings) {
    CAPTURE(k);
    Eigen::Vector3d expected = fieldAt(k);
    if (k >= 10 && k < 15) expected.x() += kBias;
    if (k >= 40 && k < 45) expected = fieldAt(40);
    CHECK(reading.valid() == !(k >= 30 && k < 33));
    if (reading.valid()) CHECK((bus::vec3(reading.b_body_T()) - expected).norm() < 1e-15);
  }
  // Events: bias on at 10, off at 15; dropout on at 30, off at 33; stuck on at 40, off at 45.
  std::lock_guard lock(script.events_mutex_);
  std::vector<std::tuple<std::string, bool, std::uint64_t>> got;
  for (const auto& e : script.events) got.emplace_back(bus::text(e.kind()), e.active(), e.header().step());
  std::sort(got.begin(), got.end(), [](const auto& a, const auto& b) { return std::get<2>(a) < std::get<2>(b); });
  const std::vector<std::tuple<std::string, bool, std::uint64_t>> expected = {
      {"bias", true, 10},    {"bias", false, 15},  {"dropout", true, 30},
      {"dropout", false, 33}, {"stuck", true, 40}, {"stuck", false, 45}};
  CHECK(got == expected);
}
