// SPDX-License-Identifier: Apache-2.0
#include "components/magnetometer_bridge/MagnetometerBridgeNode.hpp"

#include <array>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include <spdlog/spdlog.h>

#include "bus/Convert.hpp"
#include "bus/Stamp.hpp"
#include "msg/MsgJson.hpp"
#include "components/Processes.hpp"
#include "components/magnetometer_bridge/SerialPort.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::magnetometer_bridge {

MagnetometerBridgeNode::MagnetometerBridgeNode(bus::Bus& bus, bus::NodeOptions options,
                                               const MagnetometerBridgeNodeParams& params)
    : Node(bus, std::move(options)),
      params_(params),
      bridge_(params.bridge, params.fields),
      parser_(params.protocol.frame),
      grants_(bus, bus::topics::kStepGrant, [this](const msg::StepGrant& g) {
        std::lock_guard lock(grant_mutex_);
        grant_ = Grant{{g.header().step(), g.header().sim_time_ns(), g.step_period_ns()},
                       std::chrono::steady_clock::now()};
      }, {}, {}, trustFor(bus::topics::kStepGrant)) {}

std::optional<bus::StepContext> MagnetometerBridgeNode::stepNow() const {
  std::lock_guard lock(grant_mutex_);
  if (!grant_ || grant_->step.period_ns <= 0) return std::nullopt;
  const auto since = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::steady_clock::now() - grant_->seen);
  const auto periods = static_cast<std::uint64_t>(
      std::llround(static_cast<double>(since.count()) / static_cast<double>(grant_->step.period_ns)));
  return bus::StepContext{grant_->step.step + periods,
                          grant_->step.sim_time_ns + static_cast<std::int64_t>(periods) * grant_->step.period_ns,
                          grant_->step.period_ns};
}

void MagnetometerBridgeNode::run() {
  // The device end may come up after us (a simulator starting, a cable plugged in).
  const auto deadline = std::chrono::steady_clock::now() + options_.peer_timeout;
  while (!std::filesystem::exists(params_.device)) {
    if (interrupted() || std::chrono::steady_clock::now() > deadline) {
      throw bus::NodeFailure(name() + ": no device at " + params_.device);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  SerialPort port(params_.device, params_.protocol.line);
  spdlog::info("{}: reading {} at {} baud, frames per {}", name(), params_.device, params_.protocol.line.baud,
               params_.protocol.file);
  publishHealth(msg::ComponentState::RUNNING, 0, "reading " + params_.device);

  std::array<std::uint8_t, 512> buffer{};
  using Clock = std::chrono::steady_clock;
  auto next_health = Clock::now();
  auto last_frame = Clock::now();
  bool late = false;
  const auto silent_s = [&] { return std::chrono::duration<double>(Clock::now() - last_frame).count(); };
  while (!interrupted()) {
    const long n = port.read(buffer, std::chrono::milliseconds(100));
    if (n < 0) throw bus::NodeFailure(name() + ": line lost on " + params_.device);
    for (long i = 0; i < n; ++i) {
      const auto sample = parser_.push(buffer[static_cast<std::size_t>(i)]);
      if (!sample) continue;
      if (late) spdlog::info("{}: frames again from {} after {:.1f} s", name(), params_.device, silent_s());
      late = false;
      last_frame = Clock::now();
      const auto out = bridge_.step(*sample);
      missed_ += out.missed_samples;
      const auto step = stepNow();
      if (!step) continue;  // the rig has not started stepping: no time to stamp it with
      msg::MagnetometerReading reading;
      bus::stamp(reading.header(), *step, name());
      bus::put(reading.b_body_T(), out.b_B_T);
      reading.saturated(out.saturated);
      reading.valid(true);
      reading_.write(reading);
    }
    if (!late && silent_s() > params_.late_after_s) {
      late = true;
      spdlog::warn("{}: late: no good frame from {} for {:.1f} s", name(), params_.device, silent_s());
      next_health = Clock::now();  // say so now, not at the next second
    }
    if (Clock::now() >= next_health) {
      const auto& c = parser_.counts();
      char silence[64] = "";
      if (late) std::snprintf(silence, sizeof silence, "late: no good frame for %.1f s; ", silent_s());
      publishHealth(msg::ComponentState::RUNNING, c.frames,
                    silence + std::string("frames ") + std::to_string(c.frames) + ", bad checksum " + std::to_string(c.bad_checksum) +
                        ", bad header " + std::to_string(c.bad_header) + ", skipped bytes " +
                        std::to_string(c.skipped_bytes) + ", bad value " + std::to_string(c.bad_value) +
                        ", missed samples " + std::to_string(missed_));
      next_health = Clock::now() + std::chrono::seconds(1);
    }
  }
  publishHealth(msg::ComponentState::STOPPED, parser_.counts().frames, "stopped");
}

std::string defaultDevicePath(const bus::NodeArgs& args) {
  return (std::filesystem::path(args.out_dir.empty() ? "." : args.out_dir) / "magnetometer.pty").string();
}

void readMagnetometerProtocol(const bus::Scenario& scenario, bus::ParamReader& r, bus::ConfigProblems& problems,
                              device_protocol::DeviceProtocol& protocol, MagnetometerFields& fields) {
  std::string file = "magnetometer.yaml";
  r.read("protocol", file);
  std::optional<std::uint32_t> baud;  // read first: a bad description must not leave it unread
  if (r.has("baud")) {
    baud = 0;
    r.read("baud", *baud);
  }
  const auto units = [](const std::string& topic, const std::string& field) -> std::optional<std::string> {
    if (topic != bus::topics::kMagnetometer.name) return std::nullopt;
    for (const auto& leaf : msg::leafFields<msg::MagnetometerReading>()) {
      if (leaf.name == field) return std::string(leaf.unit);
    }
    return std::nullopt;
  };
  const std::size_t before = problems.list().size();
  protocol = device_protocol::readDeviceProtocol(device_protocol::findDeviceDescription(scenario.file, file), units, problems);
  if (problems.list().size() > before) return r.problem("protocol", "'" + file + "' is not a usable description (above)");
  if (protocol.topic != bus::topics::kMagnetometer.name) {
    return r.problem("protocol", "'" + file + "' describes frames for " + protocol.topic + ", not " +
                                     std::string(bus::topics::kMagnetometer.name));
  }
  // The bridge turns sensor axes into body axes by the magnetometer's mounting, and by no other.
  if (protocol.sensor_axes != "magnetometer") {
    r.problem("protocol", "'" + file + "' gives sensor_axes '" + protocol.sensor_axes +
                              "': a magnetometer's frames are in spacecraft.sensors.magnetometer's axes");
  }
  std::string why;
  if (const auto found = MagnetometerFields::of(protocol.frame, why)) {
    fields = *found;
  } else {
    r.problem("protocol", "'" + file + "': " + why);
  }
  if (baud) protocol.line.baud = *baud;
  r.problems(protocol.line.validate());
}

MagnetometerBridgeNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                        const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  MagnetometerBridgeNodeParams p;
  p.bridge.q_body_sensor = vehicle.onboard.sensors.q_body_magnetometer;  // flight software's belief
  p.device = defaultDevicePath(args);
  auto r = scenario.componentParams(args.name, problems);
  vehicle::refuseMovedKeys(r, {{"q_body_sensor", "spacecraft.sensors.magnetometer.q_body_sensor"}});
  r.read("device", p.device);
  readMagnetometerProtocol(scenario, r, problems, p.protocol, p.fields);
  r.read("range_T", p.bridge.range_T, "T");
  r.read("late_after_s", p.late_after_s, "s");
  if (!(p.late_after_s > 0.0 && std::isfinite(p.late_after_s))) r.problem("late_after_s", "must be > 0");
  r.problems(p.bridge.validate());
  r.finish();
  return p;
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<MagnetometerBridgeNode>(argc, argv, "magnetometer_bridge", vehicle::withVehicle(readParams),
                                                bus::kBridgeStrength);
}

}  // namespace flatsat::magnetometer_bridge
