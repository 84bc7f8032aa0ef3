// SPDX-License-Identifier: Apache-2.0
// A hostile or broken participant for the trust tests (architecture, "Trust
// on the bus"): on FLATSAT_DOMAIN, loopback only, it follows the rig's step
// through the grants and writes well-formed samples of the real types that no
// rig should take at face value, until SECONDS have passed or SIGTERM.
//   hostile_participant MODE SECONDS NAME [STRENGTH]
// NAME is its participant's name (a component's, to pose as that component);
// STRENGTH its ownership strength on stepped topics (default 100, a bridge's).
// MODE:
//   forge-stop   a stop grant for the next step, every 100 ms
//   nan-gyro     a gyro reading of NaN rates at each step granted
//   huge-gyro    a gyro reading of ±1e300 rad/s at each step granted
//   huge-dipole  a dipole command of ±1e300 A m² at each step granted
//   magnetometer a plausible magnetometer reading at each step granted
//   future       gyro readings stamped 1,000 steps and more past the rig's, as fast as it can
// FLATSAT_SECURE_DIR: DDS Security with NAME's certificate and grant.
// Prints what it wrote as `hostile: MODE wrote N samples`, or `hostile: MODE
// refused: REASON` (exit 3) when the bus would not make its writer.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "bus/Bus.hpp"
#include "bus/Endpoints.hpp"
#include "bus/Security.hpp"
#include "bus/Shutdown.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"

namespace {

using namespace flatsat;

template <class Def, class Fill>
std::uint64_t writeEachStep(bus::Bus& bus, const Def& def, const std::string& name, Fill fill,
                            std::chrono::steady_clock::time_point end) {
  bus::Writer<Def> writer(bus, def);
  std::atomic<std::uint64_t> newest{0};
  std::atomic<bool> granted{false};
  std::atomic<std::int64_t> period_ns{100'000'000};
  bus::ReaderOf<bus::topics::kStepGrant> grants(bus, bus::topics::kStepGrant, [&](const msg::StepGrant& g) {
    if (g.stop()) return;
    if (g.header().step() >= newest) newest = g.header().step();
    period_ns = g.step_period_ns();
    granted = true;
  });
  std::uint64_t written = 0;
  std::uint64_t last = std::numeric_limits<std::uint64_t>::max();
  while (!bus::shutdownRequested() && std::chrono::steady_clock::now() < end) {
    const std::uint64_t k = newest;
    if (granted && k != last) {
      last = k;
      typename Def::Type sample;
      bus::stamp(sample.header(), {k, static_cast<std::int64_t>(k) * period_ns, period_ns}, name);
      fill(sample);
      writer.write(sample);
      ++written;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  return written;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: hostile_participant MODE SECONDS NAME [STRENGTH]\n");
    return 2;
  }
  const std::string mode = argv[1];
  const std::chrono::steady_clock::time_point end =
      std::chrono::steady_clock::now() +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(std::atof(argv[2])));
  const std::string name = argv[3];
  bus::installShutdownHandlers();
  // Liveliness and deadline offered at 100 ms: compatible with lockstep readers
  // (which ask for none) and paced ones with a lease of 100 ms or more.
  bus::QosTuning tuning;
  tuning.watch_liveliness = true;
  tuning.lease = std::chrono::milliseconds(100);
  tuning.ownership_strength = argc > 4 ? std::atoi(argv[4]) : bus::kBridgeStrength;
  // With FLATSAT_SECURE_DIR: NAME's certificate and grant, as a stolen key would give.
  bus::Bus bus({.domain_id = bus::domainFromEnvironment(0),
                .participant_name = name,
                .tuning = tuning,
                .security_dir = bus::securityDirFromEnvironment()});
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::uint64_t written = 0;
  try {
    if (mode == "forge-stop") {
      bus::WriterOf<bus::topics::kStepGrant> writer(bus, bus::topics::kStepGrant);
      std::atomic<std::uint64_t> newest{0};
      bus::ReaderOf<bus::topics::kStepGrant> grants(bus, bus::topics::kStepGrant, [&](const msg::StepGrant& g) {
        if (!g.stop() && g.header().step() > newest) newest = g.header().step();
      });
      while (!bus::shutdownRequested() && std::chrono::steady_clock::now() < end) {
        msg::StepGrant stop;
        const std::uint64_t k = newest + 1;
        bus::stamp(stop.header(), {k, static_cast<std::int64_t>(k) * 100'000'000, 100'000'000}, "dynamics_server");
        stop.step_period_ns(100'000'000);
        stop.final_step(k);
        stop.stop(true);
        writer.write(stop);
        ++written;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
    } else if (mode == "nan-gyro" || mode == "huge-gyro") {
      const double value = mode == "nan-gyro" ? kNaN : 1e300;
      written = writeEachStep(bus, bus::topics::kGyro, name, [value](msg::GyroReading& s) {
        s.w_body_rad_s({value, -value, value});
        s.valid(true);
      }, end);
    } else if (mode == "huge-dipole") {
      written = writeEachStep(bus, bus::topics::kDipoleCmd, name, [](msg::DipoleCmd& s) {
        s.m_body_Am2({1e300, -1e300, 1e300});
        s.active(true);
      }, end);
    } else if (mode == "magnetometer") {
      written = writeEachStep(bus, bus::topics::kMagnetometer, name, [](msg::MagnetometerReading& s) {
        s.b_body_T({2e-5, -1e-5, 3e-5});
        s.valid(true);
      }, end);
    } else if (mode == "future") {
      bus::WriterOf<bus::topics::kGyro> writer(bus, bus::topics::kGyro);
      std::atomic<std::uint64_t> newest{0};
      bus::ReaderOf<bus::topics::kStepGrant> grants(bus, bus::topics::kStepGrant, [&](const msg::StepGrant& g) {
        if (!g.stop() && g.header().step() > newest) newest = g.header().step();
      });
      for (std::uint64_t i = 0; !bus::shutdownRequested() && std::chrono::steady_clock::now() < end; ++i) {
        msg::GyroReading s;
        const std::uint64_t k = newest + 1000 + i;
        bus::stamp(s.header(), {k, static_cast<std::int64_t>(k) * 100'000'000, 100'000'000}, name);
        s.w_body_rad_s({1e-3, 0.0, 0.0});
        s.valid(true);
        writer.write(s);
        ++written;
        if (i % 100 == 99) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    } else {
      std::fprintf(stderr, "hostile_participant: unknown mode '%s'\n", mode.c_str());
      return 2;
    }
  } catch (const std::runtime_error& e) {  // a grant that does not allow the writer
    std::printf("hostile: %s refused: %s\n", mode.c_str(), e.what());
    return 3;
  }
  std::printf("hostile: %s wrote %llu samples\n", mode.c_str(), static_cast<unsigned long long>(written));
  return 0;
}
