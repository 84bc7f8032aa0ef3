// SPDX-License-Identifier: Apache-2.0
#include "tools/MiddlewareBench.hpp"
#include "analysis/Quantile.hpp"
#include "tools/BenchPeers.hpp"
#include "tools/PlainGraphBench.hpp"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "bus/Bus.hpp"
#include "bus/Component.hpp"
#include "bus/Endpoints.hpp"
#include "bus/Shutdown.hpp"
#include "bus/Stamp.hpp"
#include "bus/TimeMaster.hpp"
#include "bus/Topics.hpp"

namespace flatsat::tools {

using analysis::quantile;
namespace {

/// The ping's step that tells the echo process to exit.
constexpr std::uint64_t kStopStep = std::numeric_limits<std::uint64_t>::max();
/// Round trips before the measured ones: discovery done, caches and the SHM
/// segments warm.
constexpr int kWarmupRoundTrips = 200;
constexpr auto kRewriteAfter = std::chrono::milliseconds(200);
/// The time master of the bare graph has the rig's name, so the components'
/// inputs find their producer in the schedule as in the rig.
constexpr const char* kMaster = "dynamics_server";
constexpr std::array<const char*, 7> kComponents = {
    "magnetometer", "sun_sensor", "gyro", "star_tracker",
    "estimator",    "attitude_controller", "unloading_controller"};

/// The rig's default network as a lockstep rig's components have it:
/// loopback UDP + SHM, unicast discovery, acknowledgements through shared
/// memory as well (bus/Bus.cpp).
bus::BusOptions loopback(std::uint32_t domain, const std::string& name) {
  return {.domain_id = domain, .profile = bus::NetworkProfile::kLoopback, .participant_name = name,
          .acks_over_shm = true};
}

/// The bare graph's processes as the launcher's lockstep rig has them: every
/// one scheduled and sharing memory, so stepped and protocol readers are
/// best-effort (bus/NodeMain.cpp processBusOptions).
bus::BusOptions bareGraph(std::uint32_t domain, const std::string& name) {
  auto options = loopback(domain, name);
  options.tuning.best_effort_readers = true;
  return options;
}

struct Hop {
  double p50_us;  ///< [µs] median one-way
  double p99_us;  ///< [µs] 99th percentile one-way
};

/// Ping on domain D's truth topic, the echo process answers on D+1's: each
/// topic of each domain has one writer, as exclusive ownership wants.
Hop measureHop(int round_trips) {
  const std::uint32_t domain = benchDomain();
  Peers peers;
  peers.start({"bench-echo", "--domain", std::to_string(domain)});
  bus::Bus ping_bus(loopback(domain, "bench-ping"));
  bus::Bus pong_bus(loopback(domain + 1, "bench-ping"));
  std::mutex mutex;
  std::condition_variable changed;
  std::atomic<std::uint64_t> echoed{0};  // also read for the error message, outside the lock
  bus::WriterOf<bus::topics::kTruth> ping(ping_bus, bus::topics::kTruth);
  bus::ReaderOf<bus::topics::kTruth> pong(pong_bus, bus::topics::kTruth, [&](const msg::TruthState& s) {
    {
      std::lock_guard lock(mutex);
      echoed.store(s.header().step());
    }
    changed.notify_one();
  });
  msg::TruthState sample;  // fixed-size fields: every sample has the rig's truth size
  bus::stamp(sample.header(), {}, "bench-ping");
  // Writes ping k until its echo is back. A ping is written again after
  // kRewriteAfter without an echo: right after discovery a sample can sit
  // unseen in a data-sharing segment until the next one (the rig's
  // TimeMaster resends a stalled step for the same reason, Fast DDS #3822).
  auto round_trip = [&](std::uint64_t k, std::chrono::seconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    sample.header().step(k);
    for (;;) {
      ping.write(sample);
      std::unique_lock lock(mutex);
      if (changed.wait_for(lock, kRewriteAfter, [&] { return echoed.load() == k; })) return;
      if (std::chrono::steady_clock::now() > deadline) {
        throw std::runtime_error("no echo of ping " + std::to_string(k) + " on flatsat/truth within " +
                                 std::to_string(timeout.count()) + " s (last echoed: " +
                                 std::to_string(echoed.load()) + ")");
      }
    }
  };

  std::uint64_t k = 1;
  round_trip(k++, std::chrono::seconds(30));  // discovery: both sides' endpoints match
  for (int i = 0; i < kWarmupRoundTrips; ++i) round_trip(k++, std::chrono::seconds(5));
  std::vector<double> one_way_us;
  one_way_us.reserve(static_cast<std::size_t>(round_trips));
  for (int i = 0; i < round_trips; ++i) {
    const auto start = std::chrono::steady_clock::now();
    round_trip(k++, std::chrono::seconds(5));
    one_way_us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / 2);
  }
  sample.header().step(kStopStep);
  ping.write(sample);
  ping.waitForAcknowledgments(std::chrono::seconds(5));
  peers.join();
  return {quantile(one_way_us, 0.5), quantile(one_way_us, 0.99)};
}

int runEcho(std::uint32_t domain) {
  spdlog::set_level(spdlog::level::warn);
  try {
    bus::Bus in_bus(loopback(domain, "bench-echo"));
    bus::Bus out_bus(loopback(domain + 1, "bench-echo"));
    bus::WriterOf<bus::topics::kTruth> out(out_bus, bus::topics::kTruth);
    std::mutex mutex;
    std::condition_variable changed;
    bool stop = false;
    // Answers on the Fast DDS thread that delivered the sample: the raw hop, no hand-over.
    bus::ReaderOf<bus::topics::kTruth> in(in_bus, bus::topics::kTruth, [&](const msg::TruthState& s) {
      if (s.header().step() != kStopStep) {
        out.write(s);
        return;
      }
      {
        std::lock_guard lock(mutex);
        stop = true;
      }
      changed.notify_one();
    });
    const auto deadline = std::chrono::steady_clock::now() + kPeerTimeout;
    std::unique_lock lock(mutex);
    while (!stop) {
      if (bus::shutdownRequested()) return 1;  // the bench gave up (Peers)
      if (std::chrono::steady_clock::now() > deadline) {
        spdlog::error("bench-echo: no stop on flatsat/truth of domain {} within {} s", domain, kPeerTimeout.count());
        return 1;
      }
      changed.wait_for(lock, std::chrono::milliseconds(100));
    }
    return 0;
  } catch (const std::exception& e) {
    spdlog::error("bench-echo: {}", e.what());
    return 1;
  }
}

bus::NodeOptions graphOptions(const std::string& name) {
  bus::NodeOptions options;
  options.name = name;
  options.schedule[kMaster] = 1;
  for (const char* component : kComponents) options.schedule[component] = 1;
  options.peer_timeout = std::chrono::duration_cast<std::chrono::milliseconds>(kPeerTimeout);
  return options;
}

/// A component of the bare graph: waits for every input of step k, then
/// publishes an empty sample of step k; no compute.
template <const auto& Out, const auto&... Ins>
class Relay final : public bus::Component {
 public:
  Relay(bus::Bus& bus, bus::NodeOptions options) : Component(bus, std::move(options)) { (addInput(Ins), ...); }

 private:
  void step(const bus::StepContext& ctx) override {
    typename std::remove_cvref_t<decltype(Out)>::Type sample;
    bus::stamp(sample.header(), ctx, name());
    out_.write(sample);
  }
  bus::WriterOf<Out>& out_ = addOutput(Out);
};

/// The bare graph's time master: publishes truth of step k with the grant,
/// waits for both controllers' commands of step k; times steps 0..final.
class BareMaster final : public bus::TimeMaster {
 public:
  BareMaster(bus::Bus& bus, std::uint64_t final_step)
      : TimeMaster(bus, graphOptions(kMaster), {.period_ns = 100'000'000, .final_step = final_step}) {
    addInput(bus::topics::kWheelTorqueCmd);
    addInput(bus::topics::kDipoleCmd);
  }
  double stepsPerSecond() const {
    return static_cast<double>(finalStep()) / std::chrono::duration<double>(last_ - first_).count();
  }

 private:
  void publishStep(const bus::StepContext& ctx) override {
    msg::TruthState truth;
    bus::stamp(truth.header(), ctx, name());
    truth.q_inertial_body({1.0, 0.0, 0.0, 0.0});  // a truth that is not a rotation is refused (bus/SampleChecks)
    truth_.write(truth);
  }
  void advance(const bus::StepContext& ctx) override {
    last_ = std::chrono::steady_clock::now();
    if (ctx.step == 0) first_ = last_;
  }
  bus::WriterOf<bus::topics::kTruth>& truth_ = addOutput(bus::topics::kTruth);
  std::chrono::steady_clock::time_point first_, last_;
};

std::unique_ptr<bus::Component> makeComponent(bus::Bus& bus, const std::string& role) {
  using namespace bus::topics;
  auto options = graphOptions(role);
  if (role == "magnetometer") return std::make_unique<Relay<kMagnetometer, kTruth>>(bus, options);
  if (role == "sun_sensor") return std::make_unique<Relay<kSunSensor, kTruth>>(bus, options);
  if (role == "gyro") return std::make_unique<Relay<kGyro, kTruth>>(bus, options);
  if (role == "star_tracker") return std::make_unique<Relay<kStarTracker, kTruth>>(bus, options);
  if (role == "estimator") {
    return std::make_unique<Relay<kAttitudeEstimate, kMagnetometer, kSunSensor, kGyro, kStarTracker>>(bus, options);
  }
  if (role == "attitude_controller") return std::make_unique<Relay<kWheelTorqueCmd, kAttitudeEstimate>>(bus, options);
  if (role == "unloading_controller") return std::make_unique<Relay<kDipoleCmd, kAttitudeEstimate>>(bus, options);
  throw std::invalid_argument("bench-node: no role '" + role + "'");
}

int runComponent(const std::string& role, std::uint32_t domain) {
  spdlog::set_level(spdlog::level::warn);
  try {
    bus::Bus bus(bareGraph(domain, role));
    makeComponent(bus, role)->run();
    return 0;
  } catch (const std::exception& e) {
    spdlog::error("bench-node {}: {}", role, e.what());
    return 1;
  }
}

/// The master runs in this process, the 7 components in their own: 8 processes.
double measureLimit(std::uint64_t steps) {
  const std::uint32_t domain = benchDomain();
  Peers peers;
  for (const char* role : kComponents) peers.start({"bench-node", role, "--domain", std::to_string(domain)});
  double steps_per_s = 0.0;
  {
    bus::Bus bus(bareGraph(domain, kMaster));
    BareMaster master(bus, steps);
    master.run();
    steps_per_s = master.stepsPerSecond();
  }
  peers.join();
  return steps_per_s;
}

template <class Measure>
bool attempt(const char* key, Measure&& measure) {
  try {
    measure();
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s: %s\n", key, e.what());
    return false;
  }
}

}  // namespace

bool printHopBench(bool quick) {
  const auto level = spdlog::get_level();
  spdlog::set_level(spdlog::level::warn);
  std::optional<Hop> hop;
  attempt("hop_us", [&] { hop = measureHop(quick ? 500 : 2000); });
  if (hop) std::printf("hop_us=%.1f\nhop_us_p99=%.1f\n", hop->p50_us, hop->p99_us);
  else std::printf("hop_us=nan\nhop_us_p99=nan\n");
  std::fflush(stdout);
  spdlog::set_level(level);
  return hop.has_value();
}

double measureLimitStepsPerSecond(bool quick) {
  const auto level = spdlog::get_level();
  spdlog::set_level(spdlog::level::warn);
  double limit = std::numeric_limits<double>::quiet_NaN();
  attempt("limit_steps_per_s", [&] { limit = measureLimit(quick ? 1000 : 3000); });
  spdlog::set_level(level);
  return limit;
}

double printMiddlewareBench(bool quick, bool* all_measured) {
  const bool hop = printHopBench(quick);
  const double plain = measurePlainGraphStepsPerSecond(quick);
  std::printf("plain_graph_steps_per_s=%.1f\n", plain);  // nan when it failed
  const double limit = measureLimitStepsPerSecond(quick);
  std::printf("limit_steps_per_s=%.1f\n", limit);
  std::fflush(stdout);
  if (all_measured != nullptr) *all_measured = hop && std::isfinite(limit) && std::isfinite(plain);
  return limit;
}

std::vector<CLI::App*> addBenchPeerCommands(CLI::App& app, int& exit_code) {
  auto domain = std::make_shared<std::uint32_t>(0);
  auto role = std::make_shared<std::string>();
  // group(""): hidden from --help, only the bench starts them.
  auto* echo = app.add_subcommand("bench-echo", "flatsat bench's echo peer")->group("");
  echo->add_option("--domain", *domain, "domain D: reads on D, answers on D+1")->required()->check(CLI::Range(0, 231));
  echo->callback([domain, &exit_code] { exit_code = runEcho(*domain); });
  auto* node = app.add_subcommand("bench-node", "flatsat bench's bare-graph component")->group("");
  node->add_option("role", *role, "component")->required()->check(
      CLI::IsMember(std::vector<std::string>(kComponents.begin(), kComponents.end())));
  node->add_option("--domain", *domain, "domain")->required()->check(CLI::Range(0, 232));
  node->callback([domain, role, &exit_code] { exit_code = runComponent(*role, *domain); });
  auto steps = std::make_shared<std::uint64_t>(0);
  auto* plain = app.add_subcommand("bench-plain", "flatsat bench's plain-graph node")->group("");
  plain->add_option("role", *role, "node")->required()->check([](const std::string& r) {
    return isPlainRole(r) ? std::string() : "no plain-graph node '" + r + "'";
  });
  plain->add_option("--domain", *domain, "domain")->required()->check(CLI::Range(0, 232));
  plain->add_option("--steps", *steps, "last step")->required();
  plain->callback([domain, role, steps, &exit_code] { exit_code = runPlainNode(*role, *domain, *steps); });
  return {echo, node, plain};
}

}  // namespace flatsat::tools
