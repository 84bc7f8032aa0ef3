// SPDX-License-Identifier: Apache-2.0
// The lockstep rig's answer to a lost sample (bus::kResendAfter): a master
// that grants a step again makes a component write that step's samples and
// StepDone again, and a reader that holds the sample already (an Input, as
// the recorder's) passes it on once.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <thread>

#include "bus/Convert.hpp"
#include "bus/Node.hpp"
#include "components/magnetometer/MagnetometerNode.hpp"
#include "tests/support/TestDomain.hpp"
#include "tests/support/Within.hpp"

namespace {

using namespace flatsat;

constexpr std::int64_t kPeriodNs = 100'000'000;

/// A consumer of magnetometer readings through a bus::Input, counting what its observer saw.
class Consumer final : public bus::Node {
 public:
  Consumer(bus::Bus& bus, bus::NodeOptions options) : Node(bus, std::move(options)) {}
  std::atomic<int> observed{0};

 private:
  bus::InputOf<bus::topics::kMagnetometer>& reading_ =
      addTap(bus::topics::kMagnetometer, [this](const msg::MagnetometerReading&) { ++observed; });
};

}  // namespace

TEST_CASE("a step granted again is written again, and an input passes each sample on once",
          "[component][dds][resend]") {
  const std::uint32_t domain = test::testDomain();
  const bus::Schedule schedule = {{"dynamics_server", 1}, {"magnetometer", 1}};
  bus::Bus master_bus({.domain_id = domain, .participant_name = "dynamics_server"});
  bus::Bus node_bus({.domain_id = domain, .participant_name = "magnetometer"});
  bus::Bus consumer_bus({.domain_id = domain, .participant_name = "consumer"});

  bus::WriterOf<bus::topics::kTruth> truth(master_bus, bus::topics::kTruth);
  bus::WriterOf<bus::topics::kStepGrant> grants(master_bus, bus::topics::kStepGrant);
  std::mutex mutex;
  std::map<std::uint64_t, int> done;      // StepDone arrivals by step
  std::map<std::uint64_t, int> readings;  // raw arrivals of readings by step
  bus::ReaderOf<bus::topics::kStepDone> done_reader(master_bus, bus::topics::kStepDone,
                                                    [&](const msg::StepDone& d) {
                                                      std::lock_guard lock(mutex);
                                                      ++done[d.header().step()];
                                                    });
  bus::ReaderOf<bus::topics::kMagnetometer> raw(master_bus, bus::topics::kMagnetometer,
                                                [&](const msg::MagnetometerReading& r) {
                                                  std::lock_guard lock(mutex);
                                                  ++readings[r.header().step()];
                                                });
  magnetometer::MagnetometerNode::Params params;
  magnetometer::MagnetometerNode node(node_bus, {"magnetometer", schedule}, params);
  Consumer consumer(consumer_bus, {"consumer", schedule});
  std::thread node_thread([&] { node.run(); });

  const auto count = [&](const std::map<std::uint64_t, int>& counts, std::uint64_t k) {
    std::lock_guard lock(mutex);
    const auto it = counts.find(k);
    return it == counts.end() ? 0 : it->second;
  };
  const auto grant = [&](std::uint64_t k, bool stop) {
    const bus::StepContext ctx{k, static_cast<std::int64_t>(k) * kPeriodNs, kPeriodNs};
    msg::StepGrant g;
    bus::stamp(g.header(), ctx, "dynamics_server");
    g.step_period_ns(kPeriodNs);
    g.final_step(0);
    g.stop(stop);
    grants.write(g);
  };
  std::atomic<bool> ready{false};
  bus::ReaderOf<bus::topics::kHealth> health(master_bus, bus::topics::kHealth, [&](const msg::Health& h) {
    if (bus::text(h.header().source()) == "magnetometer" && h.state() == msg::ComponentState::READY) ready = true;
  });
  // As the time master does: nothing is written before the node is READY (a write
  // delivered in-process while the node still waits for its producers would take the
  // node's lock under Fast DDS's reader lock, the reverse of the node's own order).
  REQUIRE(test::within(20, [&] { return ready.load(); }));
  msg::TruthState state;
  bus::stamp(state.header(), {0, 0, kPeriodNs}, "dynamics_server");
  state.q_inertial_body({1.0, 0.0, 0.0, 0.0});  // a truth's attitude is a unit quaternion (bus/SampleChecks)
  bus::put(state.b_body_T(), Eigen::Vector3d(2e-5, -1e-5, 3e-5));
  truth.write(state);

  grant(0, false);
  REQUIRE(test::within(10, [&] { return count(done, 0) == 1 && consumer.observed == 1; }));
  CHECK(count(readings, 0) == 1);

  grant(0, false);  // the same step again, as TimeMaster::resendStep does after a stall
  REQUIRE(test::within(10, [&] { return count(done, 0) == 2 && count(readings, 0) == 2; }));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  CHECK(consumer.observed == 1);  // the copy was dropped by the input

  grant(1, true);
  node_thread.join();
}
