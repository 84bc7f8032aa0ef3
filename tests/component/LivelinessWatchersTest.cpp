// SPDX-License-Identifier: Apache-2.0
// Readers that watch their writers' liveliness (bus::Bus::createReader): out
// of the rig's partition while a reader is made or deleted, matched again
// afterwards, and the Fast DDS 2.9.1 race this guards against (a reader made
// while a watched writer's liveliness changes) does not take a process down.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <fastdds/dds/core/status/LivelinessChangedStatus.hpp>

#include "bus/Endpoints.hpp"
#include "bus/Topics.hpp"
#include "tests/support/Background.hpp"
#include "tests/support/HealthSample.hpp"
#include "tests/support/TestDomain.hpp"
#include "tests/support/Within.hpp"

using namespace flatsat;

TEST_CASE("a liveliness watcher is unmatched while a reader is made, then hears its writers again",
          "[component][dds][watchers]") {
  const std::uint32_t domain = test::testDomain();
  bus::Bus writer_bus({.domain_id = domain, .participant_name = "gyro"});
  bus::Bus bus({.domain_id = domain, .participant_name = "watcher"});
  bus::WriterOf<bus::topics::kHealth> health(writer_bus, bus::topics::kHealth);
  health.write(test::healthSample("gyro", 1));
  health.assertLiveliness();

  std::atomic<std::uint64_t> last_steps{0};
  std::atomic<int> alive{0};
  bus::ReaderOf<bus::topics::kHealth> watcher(
      bus, bus::topics::kHealth, [&](const msg::Health& h) { last_steps = h.steps_done(); },
      [&](const std::string& source, bool is_alive) {
        if (is_alive && source == "gyro") ++alive;
      });
  REQUIRE(test::within(5.0, [&] { return watcher.matchedWriters() == 1 && last_steps == 1 && alive == 1; }));

  std::atomic<int> events{0};
  std::unique_ptr<bus::ReaderOf<bus::topics::kFaultEvent>> plain;
  {
    const bus::Bus::WatchersHeld held(bus);
    CHECK(watcher.matchedWriters() == 0);  // unmatched within the hold, not some time later
    plain = std::make_unique<bus::ReaderOf<bus::topics::kFaultEvent>>(
        bus, bus::topics::kFaultEvent, [&](const msg::FaultEvent&) { ++events; });
    health.write(test::healthSample("gyro", 2));  // written while the watcher is out of the partition
    health.assertLiveliness();
    CHECK(watcher.matchedWriters() == 0);
  }
  // Matched again, the watcher gets the writer's history (the last health, transient local)
  // and hears the writer alive once more.
  CHECK(test::within(5.0, [&] { return watcher.matchedWriters() == 1 && last_steps == 2 && alive == 2; }));

  bus::WriterOf<bus::topics::kFaultEvent> fault_events(writer_bus, bus::topics::kFaultEvent);
  REQUIRE(test::within(5.0, [&] { return plain->matchedWriters() == 1; }));
  fault_events.write(msg::FaultEvent{});
  CHECK(test::within(5.0, [&] { return events == 1; }));

  // A reader deleted without a hold of the caller's is held for by the bus all the same.
  plain.reset();
  CHECK(test::within(5.0, [&] { return watcher.matchedWriters() == 1; }));
  health.write(test::healthSample("gyro", 3));
  CHECK(test::within(5.0, [&] { return last_steps == 3; }));
}

TEST_CASE("a reader is not made while Fast DDS walks the readers for a liveliness change",
          "[component][dds][watchers]") {
  // A writer's first sample turns it "alive" for the readers that watch it, and Fast DDS 2.9.1
  // then walks the participant's list of readers (WLP::sub_liveliness_changed) without a lock,
  // calling each watcher's listener on the way. A reader made meanwhile can move the list to new
  // memory under the walk: the SIGSEGV in CI. Here one watcher's listener holds the walk open
  // for 200 ms while readers are made; they must wait for it. With the watchers left in the rig's
  // partition they did not, in 7 of 10 runs (in the others Fast DDS's transport lock happened
  // to hold them); with the hold, they waited in 10 of 10.
  const std::uint32_t domain = test::testDomain();
  bus::QosTuning tuning;  // a paced rig's: stepped readers watch their writers (ownership)
  tuning.watch_liveliness = true;
  tuning.lease = std::chrono::milliseconds(1000);
  bus::Bus bus({.domain_id = domain, .participant_name = "watcher", .tuning = tuning});

  struct SlowWatcher final : eprosima::fastdds::dds::DataReaderListener {
    std::atomic<bool> in_walk{false};
    std::atomic<bool> walked{false};
    void on_liveliness_changed(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::LivelinessChangedStatus& status) override {
      if (status.alive_count_change <= 0 || in_walk.exchange(true)) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      walked = true;
    }
  } slow;
  const auto watcher = [&] {
    return std::make_unique<bus::ReaderOf<bus::topics::kMagnetometer>>(
        bus, bus::topics::kMagnetometer, [](const msg::MagnetometerReading&) {});
  };
  auto& topic =
      bus.topic(std::string(bus::topics::kMagnetometer.name), new msg::MagnetometerReadingPubSubType());
  auto* slow_reader = bus.createReader(topic, bus::readerQos(bus::QosKind::kStepped, tuning), &slow);
  const auto second = watcher();
  const auto third = watcher();

  // The writer in a process of its own, as in a rig (in one process, Fast DDS's own locks
  // would keep the readers from being made during the walk).
  const test::Background writer(
      std::string(OWNERSHIP_TEST_WRITER) + " " + std::to_string(domain) + " 10 gyro 1000", "/dev/null");
  REQUIRE(test::within(10.0, [&] { return slow.in_walk.load(); }));
  std::vector<std::unique_ptr<bus::ReaderOf<bus::topics::kFaultEvent>>> readers;
  for (int i = 0; i < 3; ++i) {
    readers.push_back(std::make_unique<bus::ReaderOf<bus::topics::kFaultEvent>>(
        bus, bus::topics::kFaultEvent, [](const msg::FaultEvent&) {}));
  }
  CHECK(slow.walked);  // the first reader made waited for the walk
  CHECK(test::within(5.0, [&] { return second->matchedWriters() == 1 && third->matchedWriters() == 1; }));
  slow_reader->set_listener(nullptr);
  bus.deleteReader(slow_reader);
}
