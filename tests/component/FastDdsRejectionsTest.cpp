// SPDX-License-Identifier: Apache-2.0
// Samples Fast DDS drops before the bus's topic types see them (bus/FastDdsLog.hpp
// says where Fast DDS 2.9.1 drops them): a
// payload larger than the type allows, and an empty one. Each is counted in
// the reader's bus, and Fast DDS's own log of them, one error per sample and
// reader until now, reaches spdlog only at its 1st, 10th, 100th, ... repeat.
// Rogue and reader share this process; with intraprocess delivery off their
// samples take the path they take between processes (shared memory, UDP).
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/log/Log.hpp>
#include <fastrtps/xmlparser/XMLProfileManager.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

#include "bus/Endpoints.hpp"
#include "bus/FastDdsLog.hpp"
#include "bus/Topics.hpp"
#include "tests/support/RogueWriter.hpp"
#include "tests/support/TestDomain.hpp"
#include "tests/support/Within.hpp"

namespace {

using namespace flatsat;
namespace fdds = eprosima::fastdds::dds;
using FaultCmdDef = std::remove_cvref_t<decltype(bus::topics::kFaultCmd)>;
using Line = std::pair<spdlog::level::level_enum, std::string>;

/// Every line logged through spdlog's default logger while it lives.
class CapturedLog {
 public:
  CapturedLog() : sink_(std::make_shared<Sink>()), previous_(spdlog::default_logger()) {
    auto logger = std::make_shared<spdlog::logger>("captured", sink_);
    logger->set_level(spdlog::level::trace);
    spdlog::set_default_logger(logger);
  }
  ~CapturedLog() {
    fdds::Log::Flush();
    spdlog::set_default_logger(previous_);
  }
  CapturedLog(const CapturedLog&) = delete;
  CapturedLog& operator=(const CapturedLog&) = delete;

  /// The lines so far, after Fast DDS's log thread handed on what it holds.
  std::vector<Line> lines() {
    fdds::Log::Flush();
    return sink_->lines();
  }
  /// Every line so far, one a line: what a failed check shows.
  std::string text() {
    std::string all;
    for (const auto& [level, line] : lines()) all += line + "\n";
    return all;
  }
  std::vector<Line> linesWith(const std::string& text) {
    std::vector<Line> found;
    for (auto& line : lines()) {
      if (line.second.find(text) != std::string::npos) found.push_back(line);
    }
    return found;
  }

 private:
  class Sink final : public spdlog::sinks::base_sink<std::mutex> {
   public:
    std::vector<Line> lines() {
      std::lock_guard lock(mutex_);
      return lines_;
    }

   protected:
    void sink_it_(const spdlog::details::log_msg& msg) override {
      lines_.emplace_back(msg.level, std::string(msg.payload.data(), msg.payload.size()));
    }
    void flush_() override {}

   private:
    std::vector<Line> lines_;
  };
  std::shared_ptr<Sink> sink_;
  std::shared_ptr<spdlog::logger> previous_;
};

/// While it lives, participants of this process reach each other as if in
/// different processes (Fast DDS's intraprocess delivery off).
class AsFromAnotherProcess {
 public:
  AsFromAnotherProcess() {
    fdds::DomainParticipantFactory::get_instance()->load_profiles();  // a profile file's settings first
    saved_ = Manager::library_settings();
    auto settings = saved_;
    settings.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
    Manager::library_settings(settings);
  }
  ~AsFromAnotherProcess() { Manager::library_settings(saved_); }
  AsFromAnotherProcess(const AsFromAnotherProcess&) = delete;
  AsFromAnotherProcess& operator=(const AsFromAnotherProcess&) = delete;

 private:
  using Manager = eprosima::fastrtps::xmlparser::XMLProfileManager;
  eprosima::fastrtps::LibrarySettingsAttributes saved_;
};

/// A reader of fault_cmd and a rogue that writes raw payloads on it, both
/// in this process; `separate`: as if they were not.
template <class Delivery>
struct RogueAndReader {
  Delivery separate;
  std::uint32_t domain = test::testDomain();
  bus::Bus reader_bus{{domain, bus::NetworkProfile::kLoopback, "reader"}};
  bus::Bus rogue_bus{{domain, bus::NetworkProfile::kLoopback, "rogue"}};
  std::atomic<int> taken{0};
  bus::ReaderOf<bus::topics::kFaultCmd> reader{reader_bus, bus::topics::kFaultCmd,
                                               [this](const msg::FaultCmd&) { ++taken; }};
  test::RogueWriter rogue{rogue_bus, bus::topics::kFaultCmd};
  /// Matched both ways: a reader that has not yet matched the writer ignores
  /// what it is sent, and on matching starts from the writer's oldest kept
  /// sample, as if earlier ones had never been written.
  RogueAndReader() {
    REQUIRE(rogue.waitForReaders(1, std::chrono::seconds(10)));
    REQUIRE(test::within(10, [this] { return reader.matchedWriters() >= 1; }));
  }
};

/// Intraprocess delivery as the process has it.
struct AsConfigured {};

/// A valid CDR header and zeros, `extra` bytes past the type's maximum.
test::Bytes oversized(std::uint32_t extra) {
  FaultCmdDef::PubSubType type;
  test::Bytes bytes(type.m_typeSize + extra, 0);
  bytes[1] = 0x01;  // CDR, little endian
  return bytes;
}

}  // namespace

TEST_CASE("payloads larger than the type allows are counted in the bus, Fast DDS's log of them stays short",
          "[component][dds][malformed]") {
  CapturedLog log;
  RogueAndReader<AsFromAnotherProcess> rig;

  constexpr std::uint64_t kSamples = 300;
  const std::uint64_t rejected_before = bus::fastDdsRejectedSamples();
  for (std::uint64_t i = 0; i < kSamples; ++i) {
    rig.rogue.write(oversized(1 + static_cast<std::uint32_t>(i % 50)));
    // Rejected samples are acknowledged. Acknowledged in batches smaller than
    // the writer's history (64): none is replaced before the reader saw it
    // (Fast DDS would report that one lost, and the bus count it so).
    if (i % 32 == 31) REQUIRE(rig.rogue.waitForAcknowledgments(std::chrono::seconds(10)));
  }
  REQUIRE(rig.rogue.waitForAcknowledgments(std::chrono::seconds(10)));
  fdds::Log::Flush();  // the count happens on Fast DDS's log thread
  CHECK(test::within(10, [&] { return rig.reader_bus.samplesDropped() >= kSamples; }));

  CHECK(rig.reader_bus.samplesDropped() == kSamples);
  CHECK(bus::fastDdsRejectedSamples() - rejected_before == kSamples);
  CHECK(rig.rogue_bus.samplesDropped() == 0);
  CHECK(rig.taken == 0);

  // Fast DDS logs one error per sample (and reader); spdlog got its 1st,
  // 10th and 100th, at error level, and the bus's own 1st, 10th and 100th drop.
  const auto lines = log.lines();
  INFO(log.text());
  const auto fastdds = log.linesWith("fastdds [RTPS_READER_HISTORY] Change payload size of");
  CHECK(fastdds.size() >= 1);
  CHECK(fastdds.size() <= 3);
  for (const auto& [level, text] : fastdds) CHECK(level == spdlog::level::err);
  CHECK(log.linesWith("reader: dropped a sample").size() == 3);
  CHECK(log.linesWith("larger than the type allows, rejected by Fast DDS) (100 so far)").size() == 1);
  CHECK(lines.size() <= 8);  // of 300 samples
}

TEST_CASE("an empty payload from another process is counted when Fast DDS reports it lost",
          "[component][dds][malformed]") {
  CapturedLog log;
  RogueAndReader<AsFromAnotherProcess> rig;

  // The empty samples never arrive (Fast DDS drops their submessage), and the
  // reader waits for them, holding back what follows, until the writer's
  // keep-last history (64) has passed them; Fast DDS then reports them lost.
  constexpr std::uint64_t kEmpty = 5;
  constexpr std::uint64_t kAfter = 64;
  for (std::uint64_t i = 0; i < kEmpty; ++i) rig.rogue.write({});
  for (std::uint64_t i = 0; i < kAfter; ++i) rig.rogue.write(test::malformedPayloads()[0]);
  CHECK(test::within(20, [&] { return rig.reader_bus.samplesDropped() >= kEmpty + kAfter; }));
  CHECK(rig.reader_bus.samplesDropped() == kEmpty + kAfter);
  const auto lines = log.lines();
  INFO(log.text());
  CHECK(log.linesWith("(reported lost by Fast DDS) (1 so far)").size() == 1);
  CHECK(lines.size() <= 4);  // the bus's 1st and 10th drop
}

TEST_CASE("an empty payload from this process reaches the bus's topic type, which counts it",
          "[component][dds][malformed]") {
  RogueAndReader<AsConfigured> rig;
  for (int i = 0; i < 5; ++i) rig.rogue.write({});
  REQUIRE(rig.rogue.waitForAcknowledgments(std::chrono::seconds(5)));
  CHECK(test::within(5, [&] { return rig.reader_bus.samplesDropped() >= 5; }));
  CHECK(rig.reader_bus.samplesDropped() == 5);
}

TEST_CASE("Fast DDS's log entries reach spdlog at their level, each message at its 1st, 10th, 100th, ... repeat",
          "[component][malformed]") {
  CapturedLog log;
  bus::fastdds_log::Consumer consumer;
  const auto entry = [](const std::string& message, fdds::Log::Kind kind) {
    return fdds::Log::Entry{message, fdds::Log::Context{nullptr, 0, "probe_function", "FLATSAT_TEST"}, kind, ""};
  };
  // Numbers (counts, GUIDs) differ from one entry to the next: still one message.
  for (int i = 1; i <= 1000; ++i) {
    consumer.Consume(entry("repeat probe " + std::to_string(i) + " from 01.0f.a" + std::to_string(i % 10) +
                               ".c2|0.0.1.4",
                           fdds::Log::Kind::Error));
  }
  for (int i = 0; i < 3; ++i) consumer.Consume(entry("warning probe", fdds::Log::Kind::Warning));

  const auto repeats = log.linesWith("fastdds [FLATSAT_TEST] repeat probe");
  REQUIRE(repeats.size() == 4);
  for (const auto& [level, text] : repeats) CHECK(level == spdlog::level::err);
  CHECK(repeats[0].second.find("(probe_function)") != std::string::npos);
  CHECK(repeats[0].second.find("times so far") == std::string::npos);
  CHECK(repeats[1].second.find("[10 times so far") != std::string::npos);
  CHECK(repeats[3].second.find("[1000 times so far") != std::string::npos);
  const auto warnings = log.linesWith("fastdds [FLATSAT_TEST] warning probe");
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].first == spdlog::level::warn);
}
