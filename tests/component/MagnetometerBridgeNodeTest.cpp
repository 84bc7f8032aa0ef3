// SPDX-License-Identifier: Apache-2.0
// The magnetometer's two bridge-side nodes together, as a rig with a real unit
// would run them: the device stand-in senses each truth sample and sends it as
// a frame on a pseudo-terminal, in sensor axes (mounted 90 deg about z); the
// bridge reads the line, turns each frame back into body axes and publishes it
// as flatsat/magnetometer, stamped with the step of the newest grant. Every
// reading is a field the truth carried, to the frame's 1 nT per axis. When the truth stops,
// so does the device, and the bridge's health says it is late.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "bus/Convert.hpp"
#include "bus/Endpoints.hpp"
#include "bus/Shutdown.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"
#include "components/magnetometer_bridge/MagnetometerBridgeNode.hpp"
#include "components/magnetometer_device/MagnetometerDeviceNode.hpp"
#include "tests/support/TestDomain.hpp"

namespace {

using namespace flatsat;
using Clock = std::chrono::steady_clock;

constexpr std::uint64_t kGrantedStep = 5;

/// The shipped description (deploy/devices/magnetometer.yaml), as both ends read it.
void useShippedProtocol(device_protocol::DeviceProtocol& protocol, magnetometer_bridge::MagnetometerFields& fields) {
  bus::ConfigProblems problems;
  const auto tesla = [](const std::string&, const std::string&) { return std::optional<std::string>("T"); };
  protocol = device_protocol::readDeviceProtocol(FLATSAT_SOURCE_DIR "/deploy/devices/magnetometer.yaml", tesla, problems);
  INFO(problems.joined());
  REQUIRE(problems.empty());
  std::string why;
  const auto found = magnetometer_bridge::MagnetometerFields::of(protocol.frame, why);
  REQUIRE(found);
  fields = *found;
}

/// The field of truth sample i, body axes: a different one each time.
Eigen::Vector3d fieldAt(int i) { return Eigen::Vector3d(20e-6 + 1e-7 * i, -10e-6, 30e-6 - 2e-7 * i); }

}  // namespace

TEST_CASE("magnetometer device and bridge nodes carry the truth field through a serial line to the bus",
          "[magnetometer_bridge][component][dds][hil]") {
  const std::uint32_t domain = test::testDomain();
  const std::string link =
      (std::filesystem::temp_directory_path() / ("flatsat-magnetometer-" + std::to_string(::getpid()) + ".pty"))
          .string();
  const Eigen::Quaterniond mounting(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));

  bus::Bus rig_bus({domain, bus::NetworkProfile::kLoopback, "dynamics_server"});
  bus::Bus device_bus({domain, bus::NetworkProfile::kLoopback, "magnetometer_device"});
  bus::Bus bridge_bus({domain, bus::NetworkProfile::kLoopback, "magnetometer_bridge"});
  std::mutex mutex;
  std::vector<msg::MagnetometerReading> readings;
  bus::ReaderOf<bus::topics::kMagnetometer> magnetometer(rig_bus, bus::topics::kMagnetometer,
                                                         [&](const msg::MagnetometerReading& r) {
                                                           std::lock_guard lock(mutex);
                                                           readings.push_back(r);
                                                         });

  std::vector<std::string> bridge_health;  // the bridge's health messages, in order
  bus::ReaderOf<bus::topics::kHealth> health(rig_bus, bus::topics::kHealth, [&](const msg::Health& h) {
    if (bus::text(h.header().source()) != "magnetometer_bridge") return;
    std::lock_guard lock(mutex);
    bridge_health.push_back(bus::text(h.message()));
  });

  magnetometer_device::MagnetometerDeviceParams device_params;
  device_params.mounting.q_body_sensor = mounting;
  device_params.link = link;
  useShippedProtocol(device_params.protocol, device_params.fields);
  magnetometer_device::MagnetometerDeviceNode device(device_bus, {"magnetometer_device", {}}, device_params);
  magnetometer_bridge::MagnetometerBridgeNodeParams bridge_params;
  bridge_params.bridge.q_body_sensor = mounting;
  bridge_params.device = link;
  bridge_params.late_after_s = 0.3;
  useShippedProtocol(bridge_params.protocol, bridge_params.fields);
  magnetometer_bridge::MagnetometerBridgeNode bridge(bridge_bus, {"magnetometer_bridge", {}}, bridge_params);
  std::thread bridge_thread([&] { bridge.run(); });

  bus::WriterOf<bus::topics::kStepGrant> grants(rig_bus, bus::topics::kStepGrant);
  bus::WriterOf<bus::topics::kTruth> truth(rig_bus, bus::topics::kTruth);
  const bus::StepContext granted{kGrantedStep, static_cast<std::int64_t>(kGrantedStep) * 100'000'000, 100'000'000};
  msg::StepGrant grant;
  bus::stamp(grant.header(), granted, "dynamics_server");
  grant.step_period_ns(100'000'000);
  grant.final_step(1000);
  std::vector<Eigen::Vector3d> sent;
  const auto deadline = Clock::now() + std::chrono::seconds(20);  // a loaded machine is slow, not wrong
  for (int i = 0; Clock::now() < deadline; ++i) {
    grants.write(grant);
    msg::TruthState t;
    bus::stamp(t.header(), granted, "dynamics_server");
    bus::put(t.q_inertial_body(), Eigen::Quaterniond::Identity());
    bus::put(t.b_body_T(), fieldAt(i));
    sent.push_back(fieldAt(i));
    truth.write(t);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::lock_guard lock(mutex);
    if (readings.size() >= 5) break;
  }
  // The truth stops, so does the device: the bridge says it is late.
  const auto said_late = [&] {
    std::lock_guard lock(mutex);
    return std::any_of(bridge_health.begin(), bridge_health.end(),
                       [](const std::string& m) { return m.rfind("late: no good frame for", 0) == 0; });
  };
  const auto quiet_deadline = Clock::now() + std::chrono::seconds(10);
  while (!said_late() && Clock::now() < quiet_deadline) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  bus::requestShutdown();
  bridge_thread.join();
  bus::clearShutdownRequest();

  CHECK(said_late());
  std::lock_guard lock(mutex);
  REQUIRE(readings.size() >= 5);
  for (const auto& r : readings) {
    CHECK(bus::text(r.header().source()) == "magnetometer_bridge");
    CHECK(r.header().step() >= kGrantedStep);
    CHECK(r.valid());
    CHECK_FALSE(r.saturated());
    // Sensor axes rounded to 1 nT each, turned back: within √3/2 nT of a field sent.
    const Eigen::Vector3d b = bus::vec3(r.b_body_T());
    double nearest = INFINITY;
    for (const auto& s : sent) nearest = std::min(nearest, (b - s).norm());
    CHECK(nearest <= std::sqrt(3.0) * 0.5e-9 + 1e-15);
  }
}
