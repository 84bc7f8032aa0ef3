// SPDX-License-Identifier: Apache-2.0
// What a node's stepped input takes from the bus (architecture, "Trust on the
// bus"): a reading that is not finite or out of its topic's range is taken as
// a dropout and counted; a writer that is not the topic's producer is ignored,
// counted once and, in lockstep, ends the node's run naming it; samples
// stamped far past the rig's step are dropped, so a flood of them leaves the
// node's memory where it was.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <fstream>
#include <limits>
#include <mutex>
#include <string>

#include "bus/Node.hpp"
#include "tests/support/TestDomain.hpp"
#include "tests/support/Within.hpp"

namespace {

using namespace flatsat;

constexpr std::int64_t kPeriodNs = 100'000'000;

/// An estimator's view of the gyro: one stepped input.
class GyroConsumer final : public bus::Node {
 public:
  GyroConsumer(bus::Bus& bus, bus::NodeOptions options) : Node(bus, std::move(options)) {}
  std::optional<msg::GyroReading> at(std::uint64_t k) const { return gyro_.atIfAny(k); }
  bool waitFor(std::uint64_t k) { return waitForInputs(k); }
  void publishNow() { publishHealth(msg::ComponentState::RUNNING, 0, "test"); }
  void grantedStep(std::uint64_t k) { granted(k); }
  void waitForPeers() { waitForProducers(); }

 private:
  bus::InputOf<bus::topics::kGyro>& gyro_ = addInput(bus::topics::kGyro);
};

msg::GyroReading reading(std::uint64_t k, double rate) {
  msg::GyroReading r;
  bus::stamp(r.header(), {k, static_cast<std::int64_t>(k) * kPeriodNs, kPeriodNs}, "gyro");
  r.w_body_rad_s({rate, -rate, 0.5 * rate});
  r.valid(true);
  return r;
}

/// The consumer's newest health, as the rig's readers see it.
struct HealthWatch {
  explicit HealthWatch(bus::Bus& bus)
      : reader(bus, bus::topics::kHealth, [this](const msg::Health& h) {
          if (bus::text(h.header().source()) != "estimator") return;
          std::lock_guard lock(mutex);
          last = h;
          ++seen;
        }) {}
  msg::Health newest() {
    std::lock_guard lock(mutex);
    return last;
  }
  std::mutex mutex;
  msg::Health last;
  std::atomic<int> seen{0};
  bus::ReaderOf<bus::topics::kHealth> reader;
};

std::uint64_t residentKiB() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6));
  }
  return 0;
}

struct Rig {
  std::uint32_t domain = test::testDomain();
  bus::Schedule schedule = {{"dynamics_server", 1}, {"gyro", 1}, {"estimator", 1}};
  bus::Bus gyro_bus{{.domain_id = domain, .participant_name = "gyro"}};
  bus::Bus consumer_bus{{.domain_id = domain, .participant_name = "estimator"}};
  bus::WriterOf<bus::topics::kGyro> gyro{gyro_bus, bus::topics::kGyro};
  GyroConsumer consumer{consumer_bus, {"estimator", schedule}};
  HealthWatch health{gyro_bus};

  void matched() {
    REQUIRE(test::within(20, [&] { return gyro.matchedReaders() > 0 && health.reader.matchedWriters() > 0; }));
  }
  msg::Health healthNow() {
    const int before = health.seen;
    consumer.publishNow();
    REQUIRE(test::within(10, [&] { return health.seen > before; }));
    return health.newest();
  }
};

}  // namespace

TEST_CASE("a reading that is not finite or out of range is taken as a dropout and counted",
          "[component][dds][trust]") {
  Rig rig;
  rig.matched();
  rig.gyro.write(reading(1, std::numeric_limits<double>::quiet_NaN()));
  rig.gyro.write(reading(2, 1e300));
  rig.gyro.write(reading(3, 0.01));
  REQUIRE(test::within(10, [&] { return rig.consumer.at(3) && rig.consumer.at(3)->header().step() == 3; }));
  for (std::uint64_t k : {1, 2}) {
    INFO("step " << k);
    const auto taken = rig.consumer.at(k);
    REQUIRE(taken);
    CHECK(taken->header().step() == k);  // a dropout of that step: lockstep still completes it
    CHECK_FALSE(taken->valid());
    for (double w : taken->w_body_rad_s()) CHECK(w == 0.0);
  }
  CHECK(rig.consumer.at(3)->valid());
  CHECK(rig.consumer.at(3)->w_body_rad_s()[0] == 0.01);
  const msg::Health h = rig.healthNow();
  CHECK(h.samples_rejected() == 2);
  CHECK(bus::text(h.rejected_by_topic()[0].topic()) == "flatsat/gyro");
  CHECK(h.rejected_by_topic()[0].count() == 2);
  CHECK(h.intruders() == 0);
}

TEST_CASE("an intruder's samples are ignored, counted once, and end a lockstep node naming it",
          "[component][dds][trust]") {
  Rig rig;
  // Over the producer's ownership strength, as a bridge: its samples reach the reader (a
  // weaker writer's are dropped by exclusive ownership before any reader sees them).
  bus::QosTuning stronger;
  stronger.ownership_strength = bus::kBridgeStrength;
  bus::Bus intruder_bus({.domain_id = rig.domain, .participant_name = "rogue", .tuning = stronger});
  bus::WriterOf<bus::topics::kGyro> intruder(intruder_bus, bus::topics::kGyro);
  rig.matched();
  REQUIRE(test::within(20, [&] { return intruder.matchedReaders() > 0; }));
  rig.gyro.write(reading(1, 0.01));
  REQUIRE(test::within(10, [&] { return rig.consumer.at(1).has_value(); }));
  for (std::uint64_t k = 2; k < 5; ++k) intruder.write(reading(k, 0.02));
  const std::string expected = "intruder on flatsat/gyro: participant 'rogue' (writer ";
  // Named once as it matched; each of its samples refused.
  REQUIRE(test::within(10, [&] { return rig.healthNow().samples_rejected() == 3; }));
  CHECK(rig.healthNow().intruders() == 1);
  // Nothing of the intruder's is held: step 4 still sees the producer's step 1.
  REQUIRE(rig.consumer.at(4));
  CHECK(rig.consumer.at(4)->header().step() == 1);
  try {
    rig.consumer.waitFor(5);
    FAIL("the lockstep wait went on past an intruder");
  } catch (const bus::NodeFailure& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find(expected) != std::string::npos);
    CHECK(what.find("participant 'rogue'") != std::string::npos);
  }
}

TEST_CASE("a weaker intruder, whose samples exclusive ownership drops, is named as it matches",
          "[component][dds][trust]") {
  Rig rig;
  bus::QosTuning weaker;
  weaker.ownership_strength = bus::kEmulatorStrength - 1;
  bus::Bus intruder_bus({.domain_id = rig.domain, .participant_name = "rogue", .tuning = weaker});
  bus::WriterOf<bus::topics::kGyro> intruder(intruder_bus, bus::topics::kGyro);
  rig.matched();
  REQUIRE(test::within(20, [&] { return intruder.matchedReaders() > 0; }));
  // It has written nothing, and what it would write never reaches the reader.
  REQUIRE(test::within(10, [&] { return rig.healthNow().intruders() == 1; }));
  CHECK(rig.healthNow().samples_rejected() == 0);
  try {
    rig.consumer.waitFor(1);
    FAIL("the lockstep wait went on past an intruder");
  } catch (const bus::NodeFailure& e) {
    CHECK(std::string(e.what()).find("intruder on flatsat/gyro: participant 'rogue' (writer ") != std::string::npos);
  }
}

TEST_CASE("a node waits for the producer its rig runs, not for a bridge that matched first",
          "[component][dds][trust][hil]") {
  // A bridge's first sample makes it the owner (exclusive ownership): were a node
  // to start on the bridge alone, the emulator's steps before it, arriving once
  // the emulator matched, would be dropped (a recorder would miss them).
  const std::uint32_t domain = test::testDomain();
  bus::QosTuning stronger;
  stronger.ownership_strength = bus::kBridgeStrength;
  bus::Bus bridge_bus({.domain_id = domain, .participant_name = "gyro_bridge", .tuning = stronger});
  bus::WriterOf<bus::topics::kGyro> bridge(bridge_bus, bus::topics::kGyro);
  bus::NodeOptions options{"estimator", {{"dynamics_server", 1}, {"gyro", 1}, {"estimator", 1}}};
  options.bridges = {"gyro_bridge"};
  options.peer_timeout = std::chrono::milliseconds(3000);
  bus::Bus consumer_bus({.domain_id = domain, .participant_name = "estimator"});
  GyroConsumer consumer(consumer_bus, options);
  REQUIRE(test::within(20, [&] { return bridge.matchedReaders() > 0; }));
  try {
    consumer.waitForPeers();
    FAIL("ready with the bridge alone");
  } catch (const bus::NodeFailure& e) {
    CHECK(std::string(e.what()) == "estimator: waiting for producers to match for 3000 ms; missing: flatsat/gyro");
  }
  bus::Bus gyro_bus({.domain_id = domain, .participant_name = "gyro"});
  bus::WriterOf<bus::topics::kGyro> gyro(gyro_bus, bus::topics::kGyro);
  CHECK_NOTHROW(consumer.waitForPeers());
}

TEST_CASE("samples stamped far past the rig's step are dropped and leave memory where it was",
          "[component][dds][trust]") {
  Rig rig;
  rig.matched();
  rig.consumer.grantedStep(10);
  rig.gyro.write(reading(10 + bus::Node::kStampWindowSteps, 0.01));  // the window's edge: taken
  REQUIRE(test::within(10, [&] { return rig.consumer.at(10 + bus::Node::kStampWindowSteps).has_value(); }));
  const auto flood = [&](std::uint64_t from, std::uint64_t count) {
    for (std::uint64_t i = 0; i < count; ++i) rig.gyro.write(reading(from + i, 0.01));
    REQUIRE(rig.gyro.waitForAcknowledgments(std::chrono::seconds(60)));
  };
  flood(1000, 5000);  // Fast DDS's pools and the log's first lines settle
  const std::uint64_t baseline_kib = residentKiB();
  flood(6000, 70000);
  const std::uint64_t after_kib = residentKiB();
  INFO("resident " << baseline_kib << " KiB before, " << after_kib << " KiB after 70,000 samples");
  CHECK(after_kib < baseline_kib + 1024);
  const msg::Health h = rig.healthNow();
  // Reliable KEEP_LAST writers may overwrite a sample a reader has not taken yet: at most all were refused.
  CHECK(h.samples_rejected() > 70000);
  CHECK(h.samples_rejected() <= 75000);
  // Nothing of the flood is held: the newest sample at any later step is the one at the window's edge.
  REQUIRE(rig.consumer.at(70000));
  CHECK(rig.consumer.at(70000)->header().step() == 10 + bus::Node::kStampWindowSteps);
}
