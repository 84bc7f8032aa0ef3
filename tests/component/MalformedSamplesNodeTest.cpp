// SPDX-License-Identifier: Apache-2.0
// A rogue participant publishes payloads that do not decode, under the right
// type names, on every topic a magnetometer node and its time master read.
// Without the bus's guarded topic types the first of them (a bad CDR
// encapsulation) throws out of a Fast DDS thread and aborts this process;
// with them every one is dropped and counted, and the run is unaffected.
#include <catch2/catch.hpp>

#include <mutex>
#include <thread>

#include <fastcdr/exceptions/BadParamException.h>

#include "bus/Convert.hpp"
#include "bus/GuardedType.hpp"
#include "bus/TimeMaster.hpp"
#include "components/magnetometer/MagnetometerNode.hpp"
#include "tests/support/FedByScript.hpp"
#include "tests/support/RogueWriter.hpp"
#include "tests/support/TestDomain.hpp"

namespace {

using namespace flatsat;

constexpr std::uint64_t kSteps = 20;
constexpr std::int64_t kPeriodNs = 100'000'000;

Eigen::Vector3d fieldAt(std::uint64_t k) { return Eigen::Vector3d(2e-5 + 1e-7 * k, -1e-5, 3e-5); }

class Script final : public bus::TimeMaster {
 public:
  Script(bus::Bus& bus, bus::NodeOptions options)
      : TimeMaster(bus, std::move(options), {kPeriodNs, kSteps - 1}) {}
  std::map<std::uint64_t, msg::MagnetometerReading> readings;

 private:
  void publishStep(const bus::StepContext& ctx) override {
    msg::TruthState truth;
    bus::stamp(truth.header(), ctx, "dynamics_server");
    truth.q_inertial_body({1.0, 0.0, 0.0, 0.0});  // a truth's attitude is a unit quaternion (bus/SampleChecks)
    bus::put(truth.b_body_T(), fieldAt(ctx.step));
    truth_.write(truth);
  }
  void advance(const bus::StepContext& ctx) override { readings[ctx.step] = reading_.at(ctx.step); }

  bus::WriterOf<bus::topics::kTruth>& truth_ = addOutput(bus::topics::kTruth);
  bus::InputOf<bus::topics::kMagnetometer>& reading_ = addInput(bus::topics::kMagnetometer);
};

}  // namespace

TEST_CASE("samples that do not decode are dropped and counted, the node runs on",
          "[component][dds][malformed]") {
  const std::uint32_t domain = test::testDomain();
  magnetometer::MagnetometerNode::Params params;
  params.model.noise_T = 0.0;  // readings equal the truth
  const bus::Schedule schedule = {{"dynamics_server", 1}, {"magnetometer", 1}};

  bus::Bus script_bus({domain, bus::NetworkProfile::kLoopback, "script"});
  bus::Bus node_bus({domain, bus::NetworkProfile::kLoopback, "magnetometer"});
  bus::Bus rogue_bus({domain, bus::NetworkProfile::kLoopback, "rogue"});
  Script script(script_bus, {"dynamics_server", schedule});
  // The rogue is let in as a producer: what is tried here is the decoder, not
  // the trust a stranger on a stepped topic meets (InputTrustTest).
  auto options = test::fedByScript({"magnetometer", schedule});
  options.trusted.push_back("rogue");
  magnetometer::MagnetometerNode node(node_bus, options, params);
  std::mutex health_mutex;
  msg::Health last_node_health;
  bus::ReaderOf<bus::topics::kHealth> health_watch(script_bus, bus::topics::kHealth,
                                                    [&](const msg::Health& h) {
                                                      if (bus::text(h.header().source()) != "magnetometer") return;
                                                      std::lock_guard lock(health_mutex);
                                                      last_node_health = h;
                                                    });

  // Topics the node reads (one reader each on its participant) and topics
  // the script reads (step_done: one reader; health: the time master's and
  // health_watch). fault_cmd has two on the node (its sensor faults' and its
  // bus faults') and the script's bus faults'.
  std::vector<std::unique_ptr<test::RogueWriter>> rogues;
  rogues.push_back(std::make_unique<test::RogueWriter>(rogue_bus, bus::topics::kTruth));
  rogues.push_back(std::make_unique<test::RogueWriter>(rogue_bus, bus::topics::kStepGrant));
  rogues.push_back(std::make_unique<test::RogueWriter>(rogue_bus, bus::topics::kFaultCmd));
  rogues.push_back(std::make_unique<test::RogueWriter>(rogue_bus, bus::topics::kStepDone));
  rogues.push_back(std::make_unique<test::RogueWriter>(rogue_bus, bus::topics::kHealth));
  const std::vector<int> readers = {1, 1, 3, 1, 2};
  const auto payloads = test::malformedPayloads();
  for (std::size_t i = 0; i < rogues.size(); ++i) {
    INFO(rogues[i]->topicName());
    REQUIRE(rogues[i]->waitForReaders(readers[i], std::chrono::seconds(10)));
    REQUIRE(rogues[i]->matchedReaders() == readers[i]);
    for (const auto& bytes : payloads) {
      rogues[i]->write(bytes);
      // Health keeps one sample per writer: each is acknowledged before the next.
      REQUIRE(rogues[i]->waitForAcknowledgments(std::chrono::seconds(5)));
    }
  }
  const auto n = static_cast<std::uint64_t>(payloads.size());
  CHECK(node_bus.samplesDropped() == 4 * n);    // truth, step_grant, fault_cmd twice
  CHECK(script_bus.samplesDropped() == 4 * n);  // step_done, health twice, fault_cmd

  std::thread node_thread([&] { node.run(); });
  script.run();
  node_thread.join();

  REQUIRE(script.readings.size() == kSteps);
  for (const auto& [k, reading] : script.readings) {
    CAPTURE(k);
    CHECK(reading.valid());
    CHECK((bus::vec3(reading.b_body_T()) - fieldAt(k)).norm() < 1e-15);
  }
  // The node's own health says how many it dropped: each of its 4 readers
  // of truth, step_grant and fault_cmd (2) dropped every one.
  std::lock_guard lock(health_mutex);
  CHECK(last_node_health.state() == msg::ComponentState::STOPPED);
  CHECK(last_node_health.samples_dropped() == 4 * n);
}

TEST_CASE("the generated deserialiser throws on a bad encapsulation, the bus's type does not",
          "[component][malformed]") {
  using GrantDef = std::remove_cvref_t<decltype(bus::topics::kStepGrant)>;
  for (const auto& bytes : test::malformedPayloads()) {
    eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(bytes.size()));
    std::copy(bytes.begin(), bytes.end(), payload.data);
    payload.length = static_cast<std::uint32_t>(bytes.size());
    msg::StepGrant grant;
    GrantDef::PubSubType generated;
    bool generated_ok = true;
    bool threw = false;
    try {
      generated_ok = generated.deserialize(&payload, &grant);
    } catch (const eprosima::fastcdr::exception::Exception&) {
      threw = true;  // what escaped into Fast DDS's thread and aborted the process
    }
    CHECK((threw || !generated_ok));
    int drops = 0;
    bus::GuardedType<GrantDef::PubSubType> guarded([&](const char*) { ++drops; });
    CHECK_FALSE(guarded.deserialize(&payload, &grant));
    CHECK(drops == 1);
  }
  // The first two (bad encapsulation) are the ones the generated code lets through.
  const auto bad = test::malformedPayloads().front();
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(bad.size()));
  std::copy(bad.begin(), bad.end(), payload.data);
  payload.length = static_cast<std::uint32_t>(bad.size());
  msg::StepGrant grant;
  GrantDef::PubSubType generated;
  CHECK_THROWS_AS(generated.deserialize(&payload, &grant), eprosima::fastcdr::exception::BadParamException);
}
