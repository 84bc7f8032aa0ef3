// SPDX-License-Identifier: Apache-2.0
// A stand-in hardware bridge for the ownership test: publishes magnetometer
// readings as `source` at 20 Hz with the given ownership strength until it
// is killed (SIGKILL: a crash) or stopped (SIGTERM: it leaves nothing in
// /dev/shm). Usage: ownership_test_writer DOMAIN STRENGTH SOURCE LEASE_MS
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "bus/Endpoints.hpp"
#include "bus/Shutdown.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"

int main(int argc, char** argv) {
  using namespace flatsat;
  if (argc != 5) return 2;
  bus::installShutdownHandlers();
  bus::QosTuning tuning;
  tuning.watch_liveliness = true;
  tuning.lease = std::chrono::milliseconds(std::atoi(argv[4]));
  tuning.ownership_strength = std::atoi(argv[2]);
  bus::Bus bus({.domain_id = static_cast<std::uint32_t>(std::atoi(argv[1])),
                .participant_name = argv[3],
                .tuning = tuning});
  bus::WriterOf<bus::topics::kMagnetometer> writer(bus, bus::topics::kMagnetometer);
  for (std::uint64_t k = 0; !bus::shutdownRequested(); ++k) {
    msg::MagnetometerReading reading;
    bus::stamp(reading.header(), {k, static_cast<std::int64_t>(k) * 50'000'000, 50'000'000}, argv[3]);
    reading.valid(true);
    writer.write(reading);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}
