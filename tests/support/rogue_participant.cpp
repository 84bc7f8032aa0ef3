// SPDX-License-Identifier: Apache-2.0
// A rogue participant for the system tests: on FLATSAT_DOMAIN it writes
// payloads that do not decode to every topic of the registry, round after
// round, until SECONDS have passed or it gets SIGTERM; then prints how many.
//   rogue_participant SECONDS
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <thread>
#include <vector>

#include "bus/Topics.hpp"
#include "tests/support/RogueWriter.hpp"

namespace {
volatile std::sig_atomic_t stop = 0;
void onSignal(int) { stop = 1; }
}  // namespace

int main(int argc, char** argv) {
  using namespace flatsat;
  if (argc != 2) {
    std::fprintf(stderr, "usage: rogue_participant SECONDS\n");
    return 2;
  }
  std::signal(SIGTERM, onSignal);
  std::signal(SIGINT, onSignal);
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(std::atoi(argv[1]));
  // Liveliness and deadline offered at 100 ms: compatible with the readers
  // of lockstep rigs (which ask for none) and of paced rigs with a lease of
  // 100 ms or more. Strength 0 (RogueWriter): on stepped topics readers
  // take its samples only until their producer's first.
  bus::QosTuning tuning;
  tuning.watch_liveliness = true;
  tuning.lease = std::chrono::milliseconds(100);
  bus::Bus bus({.domain_id = bus::domainFromEnvironment(0), .participant_name = "rogue", .tuning = tuning});
  std::vector<std::unique_ptr<test::RogueWriter>> writers;
  bus::forEachTopic([&](const auto& def) {
    writers.push_back(std::make_unique<test::RogueWriter>(bus, def, bus.tuning()));
  });
  const auto payloads = test::malformedPayloads();
  std::uint64_t written = 0;
  for (std::size_t round = 0; !stop && std::chrono::steady_clock::now() < end; ++round) {
    for (auto& writer : writers) {
      if (writer->matchedReaders() == 0) continue;
      writer->write(payloads[round % payloads.size()]);
      ++written;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::printf("rogue: wrote %llu malformed samples on %zu topics\n",
              static_cast<unsigned long long>(written), writers.size());
  return 0;
}
