// SPDX-License-Identifier: Apache-2.0
// The in-process bus of a composed rig (bus/LocalHub.hpp) and its scheduler
// (bus/Composed.hpp): no DDS participant is created anywhere in this file.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "bus/Composed.hpp"
#include "bus/Endpoints.hpp"
#include "bus/LocalHub.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"
#include "tests/support/HealthSample.hpp"

using namespace flatsat;
namespace topics = bus::topics;

namespace {

bus::BusOptions options(const std::string& name) {
  bus::BusOptions o;
  o.participant_name = name;
  return o;
}

}  // namespace

TEST_CASE("an in-process write reaches every reader of the topic before it returns", "[bus][local]") {
  bus::LocalHub hub;
  bus::Bus a(options("a"), hub), b(options("b"), hub);
  std::vector<std::uint64_t> first, second;
  bus::ReaderOf<topics::kHealth> r1(a, topics::kHealth, [&](const msg::Health& h) { first.push_back(h.steps_done()); });
  bus::WriterOf<topics::kHealth> writer(b, topics::kHealth);
  bus::ReaderOf<topics::kHealth> r2(b, topics::kHealth, [&](const msg::Health& h) { second.push_back(h.steps_done()); });
  CHECK(writer.matchedReaders() == 2);
  CHECK(r1.matchedWriters() == 1);
  writer.write(test::healthSample("w", 7));
  CHECK(first == std::vector<std::uint64_t>{7});
  CHECK(second == std::vector<std::uint64_t>{7});
  CHECK(writer.waitForAcknowledgments(std::chrono::milliseconds(0)));
  // Another topic's readers see nothing.
  int faults = 0;
  bus::ReaderOf<topics::kFaultCmd> other(a, topics::kFaultCmd, [&](const msg::FaultCmd&) { ++faults; });
  writer.write(test::healthSample("w", 8));
  CHECK(faults == 0);
  CHECK(other.matchedWriters() == 0);
}

TEST_CASE("a reader created later gets what a transient-local writer keeps, as in DDS", "[bus][local]") {
  bus::LocalHub hub;
  bus::Bus bus(options("x"), hub);
  // Health (kState): the writer keeps its last sample (depth 1).
  bus::WriterOf<topics::kHealth> state(bus, topics::kHealth);
  for (std::uint64_t i = 1; i <= 3; ++i) state.write(test::healthSample("x", i));
  std::vector<std::uint64_t> late;
  bus::ReaderOf<topics::kHealth> reader(bus, topics::kHealth, [&](const msg::Health& h) { late.push_back(h.steps_done()); });
  CHECK(late == std::vector<std::uint64_t>{3});

  // Commands (kCommand): the last 64 of each writer, oldest first.
  auto commands = std::make_unique<bus::WriterOf<topics::kFaultCmd>>(bus, topics::kFaultCmd);
  for (std::uint64_t id = 1; id <= 70; ++id) {
    msg::FaultCmd command;
    command.command_id(id);
    commands->write(command);
  }
  std::vector<std::uint64_t> ids;
  const auto collect = [&](const msg::FaultCmd& c) { ids.push_back(c.command_id()); };
  {
    bus::ReaderOf<topics::kFaultCmd> late_commands(bus, topics::kFaultCmd, collect);
    REQUIRE(ids.size() == 64);
    CHECK(ids.front() == 7);
    CHECK(ids.back() == 70);
  }
  // A deleted writer's samples go with it.
  commands.reset();
  ids.clear();
  bus::ReaderOf<topics::kFaultCmd> after(bus, topics::kFaultCmd, collect);
  CHECK(ids.empty());
  CHECK(after.matchedWriters() == 0);
}

TEST_CASE("a sealed hub keeps nothing for late readers and refuses one", "[bus][local]") {
  bus::LocalHub hub;
  bus::Bus bus(options("x"), hub);
  bus::WriterOf<topics::kHealth> state(bus, topics::kHealth);
  std::vector<std::uint64_t> seen;
  bus::ReaderOf<topics::kHealth> reader(bus, topics::kHealth, [&](const msg::Health& h) { seen.push_back(h.steps_done()); });
  hub.seal();
  for (std::uint64_t i = 1; i <= 3; ++i) state.write(test::healthSample("x", i));
  CHECK(seen == std::vector<std::uint64_t>{1, 2, 3});  // delivery goes on
  const auto late = [&] {
    bus::ReaderOf<topics::kHealth> r(bus, topics::kHealth, [](const msg::Health&) {});
  };
  CHECK_THROWS_WITH(late(), Catch::Contains("after it started"));
  // A topic first used after the seal is sealed too.
  const auto late_command_reader = [&] {
    bus::ReaderOf<topics::kFaultCmd> r(bus, topics::kFaultCmd, [](const msg::FaultCmd&) {});
  };
  CHECK_THROWS_WITH(late_command_reader(), Catch::Contains("after it started"));
}

TEST_CASE("an in-process bus has no DDS participant and says so", "[bus][local]") {
  bus::LocalHub hub;
  bus::Bus bus(options("x"), hub);
  CHECK(bus.localHub() == &hub);
  CHECK_THROWS_AS(bus.participant(), std::logic_error);
}

namespace {

/// Publishes truth, applies the wheel command stamped with the same step.
class Master final : public bus::TimeMaster {
 public:
  Master(bus::Bus& bus, bus::NodeOptions o, std::uint64_t final_step)
      : TimeMaster(bus, std::move(o), {100'000'000, final_step}) {}
  std::vector<std::uint64_t> applied;  // the command's stamp, at each step

 private:
  void publishStep(const bus::StepContext& ctx) override {
    msg::TruthState truth;
    bus::stamp(truth.header(), ctx, name());
    truth_.write(truth);
  }
  void advance(const bus::StepContext& ctx) override {
    applied.push_back(command_.at(ctx.step).header().step());
  }
  bus::WriterOf<topics::kTruth>& truth_ = addOutput(topics::kTruth);
  bus::InputOf<topics::kWheelTorqueCmd>& command_ = addInput(topics::kWheelTorqueCmd);
};

/// One input to one output, stamped with the step.
template <const auto& In, const auto& Out>
class Relay final : public bus::Component {
 public:
  Relay(bus::Bus& bus, bus::NodeOptions o) : Component(bus, std::move(o)) {}
  std::vector<std::uint64_t> seen;  // the input's stamp, at each step

 private:
  void step(const bus::StepContext& ctx) override {
    seen.push_back(in_.at(ctx.step).header().step());
    typename std::remove_cvref_t<decltype(Out)>::Type sample;
    bus::stamp(sample.header(), ctx, name());
    out_.write(sample);
  }
  bus::InputOf<In>& in_ = addInput(In);
  bus::WriterOf<Out>& out_ = addOutput(Out);
};

bus::NodeOptions nodeOptions(const std::string& name) {
  bus::NodeOptions o;
  o.name = name;
  o.schedule = {{"dynamics_server", 1}, {"gyro", 1}, {"estimator", 1}, {"attitude_controller", 1}};
  o.peer_timeout = std::chrono::milliseconds(0);
  o.step_timeout = std::chrono::milliseconds(0);
  return o;
}

}  // namespace

TEST_CASE("the composed scheduler runs a chain in data-flow order whatever order it is given",
          "[bus][local]") {
  bus::LocalHub hub;
  bus::Bus bus(options("rig"), hub);
  Master master(bus, nodeOptions("dynamics_server"), 4);
  Relay<topics::kTruth, topics::kGyro> gyro(bus, nodeOptions("gyro"));
  Relay<topics::kGyro, topics::kAttitudeEstimate> estimator(bus, nodeOptions("estimator"));
  Relay<topics::kAttitudeEstimate, topics::kWheelTorqueCmd> controller(bus, nodeOptions("attitude_controller"));
  // Consumers first: the first step finds that they must wait for their producers.
  bus::ComposedScheduler scheduler(master, {&controller, &estimator, &gyro});
  std::vector<std::uint64_t> after;
  scheduler.run([&](std::uint64_t k) { after.push_back(k); });
  const std::vector<std::uint64_t> steps{0, 1, 2, 3, 4};
  CHECK(after == steps);
  CHECK(gyro.seen == steps);
  CHECK(estimator.seen == steps);
  CHECK(controller.seen == steps);
  CHECK(master.applied == steps);  // lockstep: each step's own command
}

TEST_CASE("a composed rig with a missing producer fails at once, naming the topic", "[bus][local]") {
  bus::LocalHub hub;
  bus::Bus bus(options("rig"), hub);
  Master master(bus, nodeOptions("dynamics_server"), 4);
  Relay<topics::kGyro, topics::kAttitudeEstimate> estimator(bus, nodeOptions("estimator"));
  bus::ComposedScheduler scheduler(master, {&estimator});
  CHECK_THROWS_WITH(scheduler.run(), Catch::Contains("flatsat/gyro"));
}
