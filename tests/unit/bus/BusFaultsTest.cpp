// SPDX-License-Identifier: Apache-2.0
// Bus faults (bus/BusFaults.hpp): which samples a drop, delay or duplicate
// hits, and which sample a consuming reader holds at each step. The answers
// must be the same in every process (a hash, not a shared generator), hit
// the set fraction of the samples with independent picks, and act exactly
// in their windows.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "bus/BusFaults.hpp"
#include "bus/Scenario.hpp"

using namespace flatsat::bus;

namespace {

constexpr std::int64_t kPeriodNs = 100'000'000;  // 0.1 s steps
const std::string kTopic = "flatsat/magnetometer";

BusFault fault(BusFaultKind kind, double magnitude, double start_s = 0.0, double duration_s = 0.0) {
  BusFault f;
  f.kind = kind;
  f.topic = kTopic;
  f.magnitude = magnitude;
  f.start_ns = std::llround(start_s * 1e9);
  f.duration_ns = std::llround(duration_s * 1e9);
  return f;
}

}  // namespace

TEST_CASE("a partial drop hits the set fraction of samples, independently, the same in every process",
          "[bus][bus_faults]") {
  BusFaultTable here(7, kPeriodNs, {fault(BusFaultKind::kDrop, 0.3)});
  BusFaultTable there(7, kPeriodNs, {fault(BusFaultKind::kDrop, 0.3)});
  BusFaultTable other_seed(8, kPeriodNs, {fault(BusFaultKind::kDrop, 0.3)});
  const auto& a = here.plan(kTopic);
  constexpr int kSamples = 100000;
  int dropped = 0, both = 0, differ_from_other_seed = 0;
  for (std::uint64_t k = 0; k < kSamples; ++k) {
    const bool d = a.dropped(k);
    REQUIRE(d == there.plan(kTopic).dropped(k));
    dropped += d;
    both += d && a.dropped(k + 1);
    differ_from_other_seed += d != other_seed.plan(kTopic).dropped(k);
  }
  // Binomial: sigma = sqrt(p (1 - p) / n) = 0.00145; 4 sigma.
  CHECK(std::abs(dropped / double(kSamples) - 0.3) < 0.0058);
  // Neighbours independent: P(both) = 0.09, sigma = 0.0009.
  CHECK(std::abs(both / double(kSamples) - 0.09) < 0.0036);
  // Another seed picks other samples: P(differ) = 2 p (1 - p) = 0.42.
  CHECK(std::abs(differ_from_other_seed / double(kSamples) - 0.42) < 0.0064);
  // Another topic picks other samples too.
  BusFault on_gyro = fault(BusFaultKind::kDrop, 0.3);
  on_gyro.topic = "flatsat/gyro";
  BusFaultTable gyro(7, kPeriodNs, {on_gyro});
  int same = 0;
  for (std::uint64_t k = 0; k < 1000; ++k) same += a.dropped(k) == gyro.plan("flatsat/gyro").dropped(k);
  CHECK(same < 700);
}

TEST_CASE("a bus fault acts exactly in its window", "[bus][bus_faults]") {
  BusFaultTable table(1, kPeriodNs,
                      {fault(BusFaultKind::kDrop, 1.0, 10.0, 2.0), fault(BusFaultKind::kDuplicate, 1.0, 5.0, 0.5)});
  const auto& plan = table.plan(kTopic);
  for (std::uint64_t k = 0; k < 300; ++k) {
    INFO("step " << k);
    CHECK(plan.dropped(k) == (k >= 100 && k < 120));
    CHECK(plan.duplicated(k) == (k >= 50 && k < 55));
    CHECK(plan.actsAt(k) == ((k >= 100 && k < 120) || (k >= 50 && k < 55)));
    CHECK(plan.delaySteps(k) == 0);
  }
  CHECK(table.plan("flatsat/gyro").empty());
  CHECK(table.faulted().size() == 1);
}

TEST_CASE("through an outage a reader holds the last sample before it, then the first after it",
          "[bus][bus_faults]") {
  SECTION("a producer every step") {
    BusFaultTable table(1, kPeriodNs, {fault(BusFaultKind::kDrop, 1.0, 10.0, 2.0)});
    const auto& plan = table.plan(kTopic);
    CHECK(plan.visibleStamp(99, 1) == 99u);
    for (std::uint64_t j = 100; j < 120; ++j) CHECK(plan.visibleStamp(j, 1) == 99u);
    CHECK(plan.visibleStamp(120, 1) == 120u);
  }
  SECTION("a producer every 2nd step, the outage starting between its samples") {
    BusFaultTable table(1, kPeriodNs, {fault(BusFaultKind::kDrop, 1.0, 10.1, 1.0)});  // steps 101..110
    const auto& plan = table.plan(kTopic);
    CHECK(plan.visibleStamp(101, 2) == 100u);  // 100 came before the outage
    CHECK(plan.visibleStamp(103, 2) == 100u);  // 102 was lost
    CHECK(plan.visibleStamp(110, 2) == 100u);  // 110 is the last lost
    CHECK(plan.visibleStamp(112, 2) == 112u);
  }
  SECTION("lost from the first sample: nothing to hold") {
    BusFaultTable table(1, kPeriodNs, {fault(BusFaultKind::kDrop, 1.0, 0.0, 1.0)});
    const auto& plan = table.plan(kTopic);
    CHECK_FALSE(plan.visibleStamp(0, 1).has_value());
    CHECK_FALSE(plan.visibleStamp(9, 1).has_value());
    CHECK(plan.visibleStamp(10, 1) == 10u);
  }
  SECTION("a partial drop: the newest sample not dropped") {
    BusFaultTable table(3, kPeriodNs, {fault(BusFaultKind::kDrop, 0.5)});
    const auto& plan = table.plan(kTopic);
    for (std::uint64_t j = 1; j < 2000; ++j) {
      const auto held = plan.visibleStamp(j, 1);
      if (!held) continue;
      CHECK_FALSE(plan.dropped(*held));
      for (std::uint64_t s = *held + 1; s <= j; ++s) CHECK(plan.dropped(s));
    }
  }
}

TEST_CASE("a delayed topic reaches its readers the set number of steps late, then on time again",
          "[bus][bus_faults]") {
  // 0.3 s late = 3 steps, for samples stamped 5.0 s .. 6.9 s (steps 50..69).
  BusFaultTable table(1, kPeriodNs, {fault(BusFaultKind::kDelay, 0.3, 5.0, 2.0)});
  const auto& plan = table.plan(kTopic);
  CHECK(plan.delaySteps(49) == 0);
  CHECK(plan.delaySteps(50) == 3);
  CHECK(plan.delaySteps(69) == 3);
  CHECK(plan.delaySteps(70) == 0);
  CHECK(plan.visibleStamp(49, 1) == 49u);
  CHECK(plan.visibleStamp(50, 1) == 49u);  // 50 arrives at 53
  CHECK(plan.visibleStamp(52, 1) == 49u);
  for (std::uint64_t j = 53; j < 70; ++j) CHECK(plan.visibleStamp(j, 1) == j - 3);
  CHECK(plan.visibleStamp(70, 1) == 70u);  // on time again: 67..69 are overtaken
  // A delay shorter than a step still misses the step.
  BusFaultTable short_delay(1, kPeriodNs, {fault(BusFaultKind::kDelay, 0.01)});
  CHECK(short_delay.plan(kTopic).delaySteps(0) == 1);
  CHECK(short_delay.plan(kTopic).visibleStamp(7, 1) == 6u);
}

TEST_CASE("bus fault values out of range are refused with the field and the reason", "[bus][bus_faults]") {
  CHECK(fault(BusFaultKind::kDrop, 1.0).validate().empty());
  CHECK(fault(BusFaultKind::kDelay, 10.0).validate().empty());
  CHECK(fault(BusFaultKind::kDrop, 0.0).validate().front().rfind("magnitude:", 0) == 0);
  CHECK(fault(BusFaultKind::kDuplicate, 1.5).validate().front().rfind("magnitude:", 0) == 0);
  CHECK(fault(BusFaultKind::kDelay, 10.5).validate().front().rfind("magnitude:", 0) == 0);
  CHECK(fault(BusFaultKind::kDrop, std::nan("")).validate().front().rfind("magnitude:", 0) == 0);
  CHECK(fault(BusFaultKind::kDrop, 1.0, -1.0).validate().front().rfind("start_s:", 0) == 0);
  BusFaultKind kind;
  CHECK(parseBusFaultKind("delay", kind));
  CHECK(kind == BusFaultKind::kDelay);
  CHECK_FALSE(parseBusFaultKind("stuck", kind));
}

TEST_CASE("a scenario's bus_faults are read, and a wrong one names its key", "[bus][bus_faults]") {
  const auto dir = std::filesystem::temp_directory_path() / ("bus-faults-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& faults) {
    const auto path = (dir / "s.yaml").string();
    std::ofstream(path) << "name: s\nduration_s: 10\ncomponents:\n  dynamics_server: {}\n" << faults;
    return path;
  };
  const auto scenario = loadScenario(write(
      "bus_faults:\n"
      "  - {kind: drop, topic: flatsat/magnetometer, magnitude: 0.5, start_s: 2, duration_s: 3}\n"
      "  - {kind: delay, topic: flatsat/gyro, magnitude: 0.2}\n"));
  REQUIRE(scenario.bus_faults.size() == 2);
  CHECK(scenario.bus_faults[0].kind == BusFaultKind::kDrop);
  CHECK(scenario.bus_faults[0].start_ns == 2'000'000'000);
  CHECK(scenario.bus_faults[0].duration_ns == 3'000'000'000);
  CHECK(scenario.bus_faults[1].topic == "flatsat/gyro");
  CHECK(scenario.bus_faults[1].magnitude == 0.2);

  const auto refused = [&](const std::string& faults) {
    try {
      loadScenario(write(faults));
    } catch (const ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK_THAT(refused("bus_faults:\n  - {kind: drop, topic: flatsat/health}\n"),
             Catch::Contains("bus_faults[0].topic: 'flatsat/health' is not a stepped topic"));
  CHECK_THAT(refused("bus_faults:\n  - {kind: lose, topic: flatsat/gyro}\n"),
             Catch::Contains("bus_faults[0].kind: 'lose' is not one of drop, delay, duplicate"));
  CHECK_THAT(refused("bus_faults:\n  - {kind: delay, topic: flatsat/gyro, magnitude: 20}\n"),
             Catch::Contains("bus_faults[0].magnitude"));
  CHECK_THAT(refused("bus_faults:\n  - {kind: drop, topic: flatsat/gyro, every: 2}\n"),
             Catch::Contains("bus_faults[0].every: unknown key"));
  std::filesystem::remove_all(dir);
}
