// SPDX-License-Identifier: Apache-2.0
// Hardware-in-the-loop swap-in (architecture, "Hardware in the loop"): a
// bridge publishing at a higher ownership strength takes over a topic from
// its emulator while it lives; SIGKILLed, readers fall back to the emulator
// within the configured liveliness lease, with no restart of anything.
#include <catch2/catch.hpp>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <atomic>
#include <mutex>
#include <thread>

#include "bus/Endpoints.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"
#include "tests/support/TestDomain.hpp"

extern char** environ;

namespace {

using namespace flatsat;
using Clock = std::chrono::steady_clock;
constexpr int kLeaseMs = 500;

struct Seen {
  std::mutex mutex;
  std::string source;
  Clock::time_point at;
};

std::string lastSource(Seen& seen) {
  std::lock_guard lock(seen.mutex);
  return seen.source;
}

/// Waits until the newest sample comes from `source`; returns how long it took.
double secondsUntil(Seen& seen, const std::string& source, double limit_s) {
  const auto start = Clock::now();
  while (lastSource(seen) != source) {
    if (std::chrono::duration<double>(Clock::now() - start).count() > limit_s) return limit_s + 1;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

TEST_CASE("a bridge overrides its emulator while alive, killed, readers fall back within the lease",
          "[device_bridge][component][dds][hil]") {
  const std::uint32_t domain = test::testDomain();
  bus::QosTuning tuning;
  tuning.watch_liveliness = true;
  tuning.lease = std::chrono::milliseconds(kLeaseMs);

  Seen seen;
  bus::Bus reader_bus({domain, bus::NetworkProfile::kLoopback, "estimator", tuning});
  bus::ReaderOf<bus::topics::kMagnetometer> reader(
      reader_bus, bus::topics::kMagnetometer, [&](const msg::MagnetometerReading& r) {
        std::lock_guard lock(seen.mutex);
        seen.source = bus::text(r.header().source());
        seen.at = Clock::now();
      });

  tuning.ownership_strength = bus::kEmulatorStrength;
  bus::Bus emulator_bus({domain, bus::NetworkProfile::kLoopback, "magnetometer", tuning});
  bus::WriterOf<bus::topics::kMagnetometer> emulator(emulator_bus, bus::topics::kMagnetometer);
  std::atomic<bool> running{true};
  std::thread emulate([&] {
    for (std::uint64_t k = 0; running; ++k) {
      msg::MagnetometerReading reading;
      bus::stamp(reading.header(), {k, 0, 0}, "magnetometer");
      emulator.write(reading);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  REQUIRE(secondsUntil(seen, "magnetometer", 10.0) < 10.0);

  const std::string exe = OWNERSHIP_TEST_WRITER;
  const std::string domain_text = std::to_string(domain), strength = std::to_string(bus::kBridgeStrength);
  const std::string lease = std::to_string(kLeaseMs);
  char* argv[] = {const_cast<char*>(exe.c_str()), const_cast<char*>(domain_text.c_str()),
                  const_cast<char*>(strength.c_str()), const_cast<char*>("bridge"),
                  const_cast<char*>(lease.c_str()), nullptr};
  pid_t bridge = -1;
  REQUIRE(posix_spawn(&bridge, exe.c_str(), nullptr, nullptr, argv, environ) == 0);
  const double takeover_s = secondsUntil(seen, "bridge", 10.0);
  CHECK(takeover_s < 10.0);  // discovery of a new participant, then its first sample wins
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  CHECK(lastSource(seen) == "bridge");  // the emulator keeps writing, but loses

  ::kill(bridge, SIGKILL);
  ::waitpid(bridge, nullptr, 0);
  const double fallback_s = secondsUntil(seen, "magnetometer", 5.0);
  INFO("takeover " << takeover_s << " s, fallback " << fallback_s << " s");
  // Lost within the lease, then the emulator's next sample (50 ms period) wins.
  CHECK(fallback_s < kLeaseMs / 1000.0 + 0.15);
  running = false;
  emulate.join();
}
