// SPDX-License-Identifier: Apache-2.0
// A described device's two bridge-side nodes together, as a rig with a real unit
// would run them: the device stand-in measures each truth sample and sends it as
// a frame on a pseudo-terminal, in the device's axes (the magnetometer mounted
// 90 deg about z); the bridge reads the line, turns each frame back into body axes
// and publishes it on the description's topic, stamped with the step of the newest
// grant. Every reading is a value the truth carried, to the frame's resolution.
// When the truth stops, so does the device, and the bridge's health says it is late.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bus/Convert.hpp"
#include "bus/Endpoints.hpp"
#include "bus/Shutdown.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"
#include "components/device_bridge/BridgeableTopics.hpp"
#include "components/device_bridge/DeviceBridgeNode.hpp"
#include "components/device_sim/DeviceSimNode.hpp"
#include "tests/support/TestDomain.hpp"

namespace {

using namespace flatsat;
using Clock = std::chrono::steady_clock;

constexpr std::uint64_t kGrantedStep = 5;

/// The shipped description deploy/devices/<device>.yaml, as both ends read it.
void useShippedProtocol(const std::string& device, device_protocol::DeviceProtocol& protocol,
                        device_bridge::FrameMapping& mapping) {
  bus::ConfigProblems problems;
  protocol = device_protocol::readDeviceProtocol(FLATSAT_SOURCE_DIR "/deploy/devices/" + device + ".yaml", device_bridge::bridgeableFieldUnit,
                                                 problems);
  INFO(problems.joined());
  REQUIRE(problems.empty());
  std::vector<std::string> names;
  for (const auto& leaf : *device_bridge::bridgeableLeaves(protocol.topic)) names.emplace_back(leaf.name);
  std::string why;
  const auto found = device_bridge::FrameMapping::of(protocol.frame, names, why);
  INFO(why);
  REQUIRE(found);
  mapping = *found;
}

/// What one device's run gave: the readings the rig saw, every truth sent, and whether
/// the bridge said it was late once the truth stopped.
template <const auto& Topic>
struct LineRun {
  std::vector<typename std::remove_cvref_t<decltype(Topic)>::Type> readings;
  std::vector<msg::TruthState> sent;
  bool said_late = false;
};

/// Device stand-in and bridge of `device` on one pseudo-terminal, the device mounted at
/// `mounting`; `truth_at(i)` is the truth sample i. Runs until 5 readings arrived.
template <const auto& Topic>
LineRun<Topic> runThroughLine(const std::string& device, const Eigen::Quaterniond& mounting,
                              const std::function<msg::TruthState(int)>& truth_at) {
  const std::uint32_t domain = test::testDomain();
  const std::string link =
      (std::filesystem::temp_directory_path() / ("flatsat-" + device + "-" + std::to_string(::getpid()) + ".pty"))
          .string();
  const std::string producer(Topic.producer);
  bus::Bus rig_bus({domain, bus::NetworkProfile::kLoopback, "dynamics_server"});
  bus::Bus device_bus({domain, bus::NetworkProfile::kLoopback, producer + "_device"});
  bus::Bus bridge_bus({domain, bus::NetworkProfile::kLoopback, producer + "_bridge"});
  std::mutex mutex;
  LineRun<Topic> run;
  bus::ReaderOf<Topic> topic(rig_bus, Topic, [&](const auto& r) {
    std::lock_guard lock(mutex);
    run.readings.push_back(r);
  });
  std::vector<std::string> bridge_health;  // the bridge's health messages, in order
  bus::ReaderOf<bus::topics::kHealth> health(rig_bus, bus::topics::kHealth, [&](const msg::Health& h) {
    if (bus::text(h.header().source()) != producer + "_bridge") return;
    std::lock_guard lock(mutex);
    bridge_health.push_back(bus::text(h.message()));
  });

  device_sim::DeviceSimParams device_params;
  device_params.mounting.q_body_sensor = mounting;
  device_params.link = link;
  useShippedProtocol(device, device_params.protocol, device_params.mapping);
  const auto& leaves = *device_bridge::bridgeableLeaves(Topic.name);
  const auto& truth_leaves = msg::leafFields<msg::TruthState>();
  device_params.topic_leaves = leaves.size();
  for (const auto& leaf : device_params.mapping.leaves) {
    if (leaves[leaf.leaf].name == "valid") continue;
    const auto it = std::find_if(truth_leaves.begin(), truth_leaves.end(),
                                 [&](const msg::FieldInfo& f) { return f.name == leaves[leaf.leaf].name; });
    REQUIRE(it != truth_leaves.end());
    device_params.sources.push_back({leaf.leaf, static_cast<std::size_t>(it - truth_leaves.begin()), 0.0});
  }
  for (std::size_t i = 0; i < leaves.size(); ++i) {
    if (leaves[i].name == "valid") device_params.valid_leaf = i;
  }
  if (std::string_view(Topic.name) == bus::topics::kSunSensor.name) device_params.fov_half_angle_rad = M_PI / 3;
  device_sim::DeviceSimNode device_node(device_bus, {producer + "_device", {}}, device_params);
  device_bridge::DeviceBridgeNodeParams bridge_params;
  bridge_params.bridge.q_body_sensor = mounting;
  bridge_params.device = link;
  bridge_params.late_after_s = 0.3;
  useShippedProtocol(device, bridge_params.protocol, bridge_params.mapping);
  device_bridge::DeviceBridgeNode bridge(bridge_bus, {producer + "_bridge", {}}, bridge_params);
  std::thread bridge_thread([&] { bridge.run(); });

  bus::WriterOf<bus::topics::kStepGrant> grants(rig_bus, bus::topics::kStepGrant);
  bus::WriterOf<bus::topics::kTruth> truth(rig_bus, bus::topics::kTruth);
  const bus::StepContext granted{kGrantedStep, static_cast<std::int64_t>(kGrantedStep) * 100'000'000, 100'000'000};
  msg::StepGrant grant;
  bus::stamp(grant.header(), granted, "dynamics_server");
  grant.step_period_ns(100'000'000);
  grant.final_step(1000);
  const auto deadline = Clock::now() + std::chrono::seconds(20);  // a loaded machine is slow, not wrong
  for (int i = 0; Clock::now() < deadline; ++i) {
    grants.write(grant);
    msg::TruthState t = truth_at(i);
    bus::stamp(t.header(), granted, "dynamics_server");
    run.sent.push_back(t);
    truth.write(t);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::lock_guard lock(mutex);
    if (run.readings.size() >= 5) break;
  }
  // The truth stops, so does the device: the bridge says it is late.
  const auto said_late = [&] {
    std::lock_guard lock(mutex);
    return std::any_of(bridge_health.begin(), bridge_health.end(),
                       [](const std::string& m) { return m.rfind("late ", 0) == 0; });
  };
  const auto quiet_deadline = Clock::now() + std::chrono::seconds(10);
  while (!said_late() && Clock::now() < quiet_deadline) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  bus::requestShutdown();
  bridge_thread.join();
  bus::clearShutdownRequest();
  run.said_late = said_late();
  std::lock_guard lock(mutex);
  for (const auto& r : run.readings) {
    CHECK(bus::text(r.header().source()) == producer + "_bridge");
    CHECK(r.header().step() >= kGrantedStep);
  }
  return run;
}

/// The truth's vector `pick(t)` nearest to `measured` among the truth sent.
double nearestSent(const std::vector<msg::TruthState>& sent, const Eigen::Vector3d& measured,
                   const std::function<Eigen::Vector3d(const msg::TruthState&)>& pick) {
  double nearest = INFINITY;
  for (const auto& t : sent) nearest = std::min(nearest, (measured - pick(t)).norm());
  return nearest;
}

}  // namespace

TEST_CASE("magnetometer device and bridge nodes carry the truth field through a serial line to the bus",
          "[device_bridge][component][dds][hil]") {
  const Eigen::Quaterniond mounting(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const auto run = runThroughLine<bus::topics::kMagnetometer>("magnetometer", mounting, [](int i) {
    msg::TruthState t;
    bus::put(t.q_inertial_body(), Eigen::Quaterniond::Identity());
    bus::put(t.b_body_T(), Eigen::Vector3d(20e-6 + 1e-7 * i, -10e-6, 30e-6 - 2e-7 * i));
    return t;
  });
  CHECK(run.said_late);
  REQUIRE(run.readings.size() >= 5);
  for (const auto& r : run.readings) {
    CHECK(r.valid());
    CHECK_FALSE(r.saturated());
    // Sensor axes rounded to 1 nT each, turned back: within √3/2 nT of a field sent.
    CHECK(nearestSent(run.sent, bus::vec3(r.b_body_T()), [](const auto& t) { return bus::vec3(t.b_body_T()); }) <=
          std::sqrt(3.0) * 0.5e-9 + 1e-15);
  }
}

TEST_CASE("gyro device and bridge nodes carry the truth rate through a serial line to the bus",
          "[device_bridge][component][dds][hil]") {
  const auto run = runThroughLine<bus::topics::kGyro>("gyro", Eigen::Quaterniond::Identity(), [](int i) {
    msg::TruthState t;
    bus::put(t.w_body_rad_s(), Eigen::Vector3d(0.01 + 1e-4 * i, -0.002, 0.05 - 3e-4 * i));
    return t;
  });
  CHECK(run.said_late);
  REQUIRE(run.readings.size() >= 5);
  for (const auto& r : run.readings) {
    CHECK(r.valid());
    // 1e-6 deg/s counts: within √3/2 of one of a rate sent.
    CHECK(nearestSent(run.sent, bus::vec3(r.w_body_rad_s()), [](const auto& t) { return bus::vec3(t.w_body_rad_s()); }) <=
          std::sqrt(3.0) * 0.5e-6 * M_PI / 180.0 + 1e-15);
  }
}

TEST_CASE("Sun sensor device and bridge nodes carry the Sun direction, and say when it is out of view",
          "[device_bridge][component][dds][hil]") {
  // The default boresight is body +x with a 60 deg cone: every other sample puts the Sun
  // behind the head, which the device reports invalid with a zero vector.
  const auto run = runThroughLine<bus::topics::kSunSensor>("sun_sensor", Eigen::Quaterniond::Identity(), [](int i) {
    msg::TruthState t;
    const double x = i % 2 == 0 ? 0.9 : -0.9;
    bus::put(t.sun_body_unit(), Eigen::Vector3d(x, 0.3, -0.1 * (i % 4)).normalized());
    t.illumination(1.0);
    return t;
  });
  CHECK(run.said_late);
  REQUIRE(run.readings.size() >= 5);
  int seen = 0, unseen = 0;
  for (const auto& r : run.readings) {
    const Eigen::Vector3d s = bus::vec3(r.sun_body_unit());
    if (r.valid()) {
      ++seen;
      CHECK(s.x() > 0.5);
      CHECK(nearestSent(run.sent, s, [](const auto& t) { return bus::vec3(t.sun_body_unit()); }) <=
            std::sqrt(3.0) * 0.5 / 32000 + 1e-15);
    } else {
      ++unseen;
      CHECK(s.isZero());
    }
    CHECK(r.cell_count() == 0u);  // a fine head
  }
  CHECK(seen > 0);
  CHECK(unseen > 0);
}

TEST_CASE("wheel tachometer device and bridge nodes carry the four wheel speeds through a serial line to the bus",
          "[device_bridge][component][dds][hil]") {
  const auto run = runThroughLine<bus::topics::kWheelTach>("wheel_tach", Eigen::Quaterniond::Identity(), [](int i) {
    msg::TruthState t;
    t.wheel_count(4);
    bus::put(t.wheel_speed_rad_s(), Eigen::Vector4d(10.0 + 0.1 * i, -20.0, 0.0, 150.0 - i));
    return t;
  });
  CHECK(run.said_late);
  REQUIRE(run.readings.size() >= 5);
  for (const auto& r : run.readings) {
    CHECK(r.valid());
    // 1 mrad/s counts: every wheel within half a count of one truth sample, all four of the same one.
    double nearest = INFINITY;
    for (const auto& t : run.sent) {
      double worst = 0.0;
      for (std::size_t w = 0; w < 4; ++w) worst = std::max(worst, std::abs(r.wheel_speed_rad_s()[w] - t.wheel_speed_rad_s()[w]));
      nearest = std::min(nearest, worst);
    }
    CHECK(nearest <= 0.5e-3 + 1e-12);
  }
}

TEST_CASE("a reaction wheel unit and its bridge: torque commands in as frames, the unit's speeds out, "
          "after its delay and within its limit",
          "[device_bridge][component][dds][hil]") {
  const std::uint32_t domain = test::testDomain();
  const std::string link =
      (std::filesystem::temp_directory_path() / ("flatsat-reaction_wheel-" + std::to_string(::getpid()) + ".pty")).string();
  bus::Bus rig_bus({domain, bus::NetworkProfile::kLoopback, "dynamics_server"});
  bus::Bus controller_bus({domain, bus::NetworkProfile::kLoopback, "attitude_controller"});
  bus::Bus device_bus({domain, bus::NetworkProfile::kLoopback, "wheel_tach_device"});
  bus::Bus bridge_bus({domain, bus::NetworkProfile::kLoopback, "wheel_tach_bridge"});
  std::mutex mutex;
  std::vector<msg::WheelTachReading> readings;
  bus::ReaderOf<bus::topics::kWheelTach> tach(rig_bus, bus::topics::kWheelTach, [&](const auto& r) {
    std::lock_guard lock(mutex);
    readings.push_back(r);
  });

  // The unit: 0.03 N m at most, 0.3 s from a command to its torque, four 0.12 kg m^2 rotors.
  device_sim::DeviceSimParams unit;
  unit.link = link;
  useShippedProtocol("reaction_wheel", unit.protocol, unit.mapping);
  std::string why;
  std::vector<std::string> command_leaves, tach_leaves;
  for (const auto& leaf : *device_bridge::bridgeableLeaves(bus::topics::kWheelTorqueCmd.name)) command_leaves.emplace_back(leaf.name);
  for (const auto& leaf : *device_bridge::bridgeableLeaves(bus::topics::kWheelTach.name)) tach_leaves.emplace_back(leaf.name);
  const auto command_mapping = device_bridge::FrameMapping::of(*unit.protocol.command, command_leaves, why);
  INFO(why);
  REQUIRE(command_mapping);
  unit.command_mapping = command_mapping;
  unit.topic_leaves = tach_leaves.size();
  for (std::size_t i = 0; i < 4; ++i) {
    const std::string k = "[" + std::to_string(i) + "]";
    unit.speed_leaves[i] = static_cast<std::size_t>(
        std::find(tach_leaves.begin(), tach_leaves.end(), "wheel_speed_rad_s" + k) - tach_leaves.begin());
    unit.torque_leaves[i] = static_cast<std::size_t>(
        std::find(command_leaves.begin(), command_leaves.end(), "torque_Nm" + k) - command_leaves.begin());
  }
  unit.wheel = device_sim::ReactionWheelDeviceParams{4, Eigen::Vector4d::Constant(0.12), 0.03, 0.3};
  device_sim::DeviceSimNode device_node(device_bus, {"wheel_tach_device", {}}, unit);
  std::thread device_thread([&] { device_node.run(); });
  device_bridge::DeviceBridgeNodeParams bridge_params;
  bridge_params.device = link;
  useShippedProtocol("reaction_wheel", bridge_params.protocol, bridge_params.mapping);
  bridge_params.command_mapping = command_mapping;
  device_bridge::DeviceBridgeNode bridge(bridge_bus, {"wheel_tach_bridge", {}}, bridge_params);
  std::thread bridge_thread([&] { bridge.run(); });

  // A scripted rig and controller: a step every 100 ms, the rotors at 1, 2, 3, 4 rad/s when
  // the truth starts; zero torques until answers reach the rig (the line and the bus are
  // up end to end), then every step the same torques, the first beyond the unit's limit.
  bus::WriterOf<bus::topics::kStepGrant> grants(rig_bus, bus::topics::kStepGrant);
  bus::WriterOf<bus::topics::kTruth> truth(rig_bus, bus::topics::kTruth);
  bus::WriterOf<bus::topics::kWheelTorqueCmd> commands(controller_bus, bus::topics::kWheelTorqueCmd);
  const Eigen::Vector4d w0(1.0, 2.0, 3.0, 4.0), asked(0.1, -0.01, 0.0, 0.02);
  constexpr std::int64_t kPeriodNs = 100'000'000;
  std::uint64_t k = kGrantedStep;
  std::optional<std::uint64_t> torquing_from;  // the step of the first torque asked
  const auto deadline = Clock::now() + std::chrono::seconds(30);  // a loaded machine is slow, not wrong
  for (auto tick = Clock::now(); Clock::now() < deadline; k++) {
    const bus::StepContext step{k, static_cast<std::int64_t>(k) * kPeriodNs, kPeriodNs};
    msg::StepGrant grant;
    bus::stamp(grant.header(), step, "dynamics_server");
    grant.step_period_ns(kPeriodNs);
    grant.final_step(100000);
    grants.write(grant);
    msg::TruthState t;
    bus::stamp(t.header(), step, "dynamics_server");
    t.wheel_count(4);
    bus::put(t.wheel_speed_rad_s(), w0);  // the unit takes only its start from the truth
    truth.write(t);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    msg::WheelTorqueCmd command;
    bus::stamp(command.header(), step, "attitude_controller");
    bus::put(command.torque_Nm(), torquing_from ? asked : Eigen::Vector4d::Zero());
    commands.write(command);
    tick += std::chrono::milliseconds(100);
    std::this_thread::sleep_until(tick);
    std::lock_guard lock(mutex);
    if (!torquing_from && readings.size() >= 3) torquing_from = k + 1;
    if (torquing_from && readings.size() >= 30 && readings.back().header().step() > *torquing_from + 20) break;
  }
  bus::requestShutdown();
  bridge_thread.join();
  device_thread.join();
  bus::clearShutdownRequest();

  std::lock_guard lock(mutex);
  REQUIRE(torquing_from);
  REQUIRE(readings.back().header().step() > *torquing_from + 20);
  // Each answer is stamped the step after the command it answers; the first ones, to zero
  // torques, keep the rotors where the truth started them.
  for (const auto& r : readings) {
    CHECK(bus::text(r.header().source()) == "wheel_tach_bridge");
    CHECK(r.header().step() > kGrantedStep);
    CHECK(r.valid());
  }
  const auto speed = [&](std::size_t n, int wheel) { return readings[n].wheel_speed_rad_s()[static_cast<std::size_t>(wheel)]; };
  for (int w = 0; w < 4; ++w) CHECK(speed(0, w) == Approx(w0(w)).margin(1e-6));
  // From the last answers: the unit's rates are its torques over the rotor inertia, the
  // first held to 0.03 N m; the commanded ones would give 0.833 rad/s^2 for it.
  const std::size_t a = readings.size() - 11, b = readings.size() - 1;
  const double dt_s = static_cast<double>(readings[b].header().sim_time_ns() - readings[a].header().sim_time_ns()) * 1e-9;
  REQUIRE(dt_s > 0.5);
  const Eigen::Vector4d torque_expected(0.03, -0.01, 0.0, 0.02);
  for (int w = 0; w < 4; ++w) {
    const double rate = (speed(b, w) - speed(a, w)) / dt_s;
    INFO("wheel " << w + 1);
    // The unit's clock runs on the truth's plus the wall time since it: a few ms of jitter per answer.
    CHECK(rate == Approx(torque_expected(w) / 0.12).margin(0.05 * 0.25));
  }
  // The delay: extrapolated back along its slope, wheel 1 began to turn 0.3 s after the
  // first torque was asked. An answer stamped s answers the command of s - 1 step.
  const double answered_s = static_cast<double>(readings[b].header().sim_time_ns()) * 1e-9 - 0.1;
  const double onset = answered_s - (speed(b, 0) - w0(0)) / (0.03 / 0.12);
  CHECK(onset - static_cast<double>(*torquing_from) * 0.1 == Approx(0.3).margin(0.05));
}
