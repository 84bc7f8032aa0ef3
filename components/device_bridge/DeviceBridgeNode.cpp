// SPDX-License-Identifier: Apache-2.0
#include "components/device_bridge/DeviceBridgeNode.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>

#include <spdlog/spdlog.h>

#include "bus/Stamp.hpp"
#include "components/Processes.hpp"
#include "components/device_bridge/BridgeableTopics.hpp"
#include "components/device_bridge/SerialPort.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::device_bridge {
namespace {

/// The producer a component named `<producer>_bridge` or `<producer>_device` stands for.
std::string producerOf(const std::string& component) {
  for (const std::string suffix : {"_bridge", "_device"}) {
    if (component.size() > suffix.size() && component.ends_with(suffix)) {
      return component.substr(0, component.size() - suffix.size());
    }
  }
  return component;
}

std::vector<std::string> leafNames(const std::vector<msg::FieldInfo>& leaves) {
  std::vector<std::string> names;
  for (const auto& leaf : leaves) names.emplace_back(leaf.name);
  return names;
}

}  // namespace

void refuseDeviceKeys(bus::ParamReader& r) {
  vehicle::refuseMovedKeys(r, {{"q_body_sensor", "spacecraft.sensors.magnetometer.q_body_sensor"}});
  if (r.has("range_T")) {
    r.problem("range_T", "a device's range is its description's: give it as full_scale on the fields (docs/devices.md)");
    r.leave({"range_T"});
  }
}

DeviceBridgeNode::DeviceBridgeNode(bus::Bus& bus, bus::NodeOptions options, const DeviceBridgeNodeParams& params)
    : Node(bus, std::move(options)),
      params_(params),
      bridge_(params.bridge, params.mapping),
      parser_(params.protocol.frame),
      publish_(publisherFor(params.protocol.topic)),
      grants_(bus, bus::topics::kStepGrant, [this](const msg::StepGrant& g) {
        if (g.stop()) run_ended_ = true;
        std::lock_guard lock(grant_mutex_);
        grant_ = Grant{{g.header().step(), g.header().sim_time_ns(), g.step_period_ns()},
                       std::chrono::steady_clock::now()};
      }, {}, {}, trustFor(bus::topics::kStepGrant)),
      commands_(subscribeCommands(bus)) {}

DeviceBridgeNode::~DeviceBridgeNode() {
  commands_.reset();  // no command callback once the port goes
}

std::shared_ptr<void> DeviceBridgeNode::subscribeCommands(bus::Bus& bus) {
  if (!params_.command_mapping) return nullptr;
  std::shared_ptr<void> reader;
  withBridgeableTopic(params_.protocol.command_topic, [&](const auto& def) {
    using Def = std::remove_cvref_t<decltype(def)>;
    using Sample = typename Def::Type;
    const std::size_t leaves = msg::leafFields<Sample>().size();
    reader = std::shared_ptr<bus::Reader<Def>>(new bus::Reader<Def>(bus, def, [this, leaves](const Sample& sample) {
      std::vector<double> values(leaves, 0.0);
      for (std::size_t i = 0; i < leaves; ++i) {
        values[i] = msg::leafValue(sample, i).value_or(0.0);
        // A command with a NaN in it never reaches a device: the device would act on it.
        if (!std::isfinite(values[i])) {
          ++commands_refused_;
          return;
        }
      }
      writeCommand(values, sample.header().step());
    }, {}, {}, trustFor(def)));
  });
  return reader;
}

void DeviceBridgeNode::writeCommand(const std::vector<double>& command_values, std::uint64_t step) {
  std::lock_guard lock(port_mutex_);
  if (!port_) return;  // the line is not open yet: no device to command
  last_command_step_ = step;
  const auto& spec = *params_.protocol.command;
  const auto frame = device_protocol::encodeFrame(
      spec, deviceFrame(command_values, params_.bridge, spec, *params_.command_mapping, command_sequence_++));
  ++(port_->write(frame) ? commands_sent_ : commands_unsent_);
}

std::function<bool(const BridgeSample&, const bus::StepContext&)> DeviceBridgeNode::publisherFor(
    const std::string& topic) {
  std::function<bool(const BridgeSample&, const bus::StepContext&)> publish;
  withBridgeableTopic(topic, [&](const auto& def) {
    using Sample = typename std::remove_cvref_t<decltype(def)>::Type;
    auto& writer = addOutput(def);
    publish = [&writer, source = name()](const BridgeSample& bridged, const bus::StepContext& step) {
      Sample sample;
      bus::stamp(sample.header(), step, source);
      for (const auto& [leaf, value] : bridged.leaves) {
        if (!msg::setLeaf(sample, leaf, value)) return false;
      }
      writer.write(sample);
      return true;
    };
  });
  if (!publish) throw std::invalid_argument(topic + ": not a topic a bridge may publish");
  return publish;
}

std::optional<bus::StepContext> DeviceBridgeNode::stepNow() const {
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

std::optional<bus::StepContext> DeviceBridgeNode::stampFor() const {
  auto now = stepNow();
  if (!now || params_.protocol.reply != device_protocol::ReplyMode::kPerCommand) return now;
  // An answer to the command of step k is the unit's state as step k + 1 begins, as the
  // plant's truth of k + 1 is its answer to the commands of k: the next step's
  // consumers (the controller) take it at once, not after waiting for their own command.
  std::lock_guard lock(port_mutex_);
  if (!last_command_step_) return now;
  const auto next = *last_command_step_ + 1;
  now->sim_time_ns += (static_cast<std::int64_t>(next) - static_cast<std::int64_t>(now->step)) * now->period_ns;
  now->step = next;
  return now;
}

std::string DeviceBridgeNode::counters() const {
  const auto& c = parser_.counts();
  // Health messages hold 95 characters (Health.idl): short words, room for large counts.
  std::string line = "frames " + std::to_string(c.frames) + ", bad: check " + std::to_string(c.bad_checksum) +
                     " header " + std::to_string(c.bad_header) + " value " + std::to_string(c.bad_value + unrepresentable_) +
                     ", skipped " + std::to_string(c.skipped_bytes) + " B, missed " + std::to_string(missed_);
  if (params_.command_mapping) {
    line += ", cmds " + std::to_string(commands_sent_) + "/" +
            std::to_string(commands_sent_ + commands_unsent_ + commands_refused_);
  }
  return line;
}

void DeviceBridgeNode::run() {
  // The device end may come up after us (a simulator starting, a cable plugged in).
  const auto deadline = std::chrono::steady_clock::now() + options_.peer_timeout;
  while (!std::filesystem::exists(params_.device)) {
    if (interrupted() || std::chrono::steady_clock::now() > deadline) {
      throw bus::NodeFailure(name() + ": no device at " + params_.device);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  {
    std::lock_guard lock(port_mutex_);
    port_ = std::make_unique<SerialPort>(params_.device, params_.protocol.line);
  }
  SerialPort& port = *port_;
  spdlog::info("{}: reading {} at {} baud, frames per {} onto {}", name(), params_.device, params_.protocol.line.baud,
               params_.protocol.file, params_.protocol.topic);
  publishHealth(msg::ComponentState::RUNNING, 0, "reading " + params_.device);
  if (params_.command_mapping) {
    spdlog::info("{}: commands from {} as {} frames to {}", name(), params_.protocol.command_topic,
                 params_.protocol.command->name, params_.device);
  }

  std::array<std::uint8_t, 512> buffer{};
  using Clock = std::chrono::steady_clock;
  auto next_health = Clock::now();
  auto last_frame = Clock::now();
  bool late = false, stepping = false;
  const auto silent_s = [&] { return std::chrono::duration<double>(Clock::now() - last_frame).count(); };
  while (!interrupted()) {
    const long n = port.read(buffer, std::chrono::milliseconds(100));
    if (n < 0 && run_ended_) {
      // The rig stops its device stand-ins with the rest: a line closing now is no fault.
      spdlog::info("{}: {} closed as the run ended", name(), params_.device);
      break;
    }
    if (n < 0) throw bus::NodeFailure(name() + ": line lost on " + params_.device);
    for (long i = 0; i < n; ++i) {
      const auto frame = parser_.push(buffer[static_cast<std::size_t>(i)]);
      if (!frame) continue;
      if (late) spdlog::info("{}: frames again from {} after {:.1f} s", name(), params_.device, silent_s());
      late = false;
      last_frame = Clock::now();
      const auto sample = bridge_.step(*frame);
      missed_ += sample.missed_samples;
      const auto step = stampFor();
      if (!step) continue;  // the rig has not started stepping: no time to stamp it with
      if ((!sample.finite || !publish_(sample, *step)) && unrepresentable_++ == 0) {
        spdlog::warn("{}: a frame holds a value its field of {} cannot take (a fraction for an integer, or out of "
                     "its range, or beyond a double once scaled): dropped, and counted as a bad value",
                     name(), params_.protocol.topic);
      }
    }
    // Before the rig steps there is no truth to measure: silence then is not lateness.
    if (!stepping && stepNow()) {
      stepping = true;
      last_frame = Clock::now();
    }
    if (stepping && !late && silent_s() > params_.late_after_s) {
      late = true;
      spdlog::warn("{}: late: no good frame from {} for {:.1f} s", name(), params_.device, silent_s());
      next_health = Clock::now();  // say so now, not at the next second
    }
    if (Clock::now() >= next_health) {
      char silence[64] = "";
      if (late) std::snprintf(silence, sizeof silence, "late %.1f s; ", silent_s());
      publishHealth(msg::ComponentState::RUNNING, parser_.counts().frames, silence + counters());
      next_health = Clock::now() + std::chrono::seconds(1);
    }
  }
  publishHealth(msg::ComponentState::STOPPED, parser_.counts().frames, "stopped; " + counters());
  std::lock_guard lock(port_mutex_);
  port_.reset();
}

std::string defaultDevicePath(const bus::NodeArgs& args, const std::string& device_name) {
  return (std::filesystem::path(args.out_dir.empty() ? "." : args.out_dir) / (device_name + ".pty")).string();
}

void readProtocol(const bus::Scenario& scenario, const std::string& component, const vehicle::SensorMountings& mountings,
                  bus::ParamReader& r, bus::ConfigProblems& problems, device_protocol::DeviceProtocol& protocol,
                  FrameMapping& mapping, std::optional<FrameMapping>& command_mapping, Eigen::Quaterniond& q_body_sensor) {
  const std::string producer = producerOf(component);
  std::string file = producer + ".yaml";
  r.read("protocol", file);
  std::optional<std::uint32_t> baud;  // read first: a bad description must not leave it unread
  if (r.has("baud")) {
    baud = 0;
    r.read("baud", *baud);
  }
  const std::size_t before = problems.list().size();
  protocol = device_protocol::readDeviceProtocol(device_protocol::findDeviceDescription(scenario.file, file), bridgeableFieldUnit, problems);
  if (problems.list().size() > before) return r.problem("protocol", "'" + file + "' is not a usable description (above)");
  const auto leaves = bridgeableLeaves(protocol.topic);
  if (!leaves) {
    return r.problem("protocol", "'" + file + "' describes frames for '" + protocol.topic +
                                     "', which is not a stepped topic of the rig with a producer");
  }
  // Its trust and grants come from its name: only <producer>_bridge may write over <producer>.
  if (bridgeableProducer(protocol.topic) != producer) {
    return r.problem("protocol", "'" + file + "' describes frames for " + protocol.topic + ", which " +
                                     bridgeableProducer(protocol.topic) + " publishes, not " + producer +
                                     " (name the component " + bridgeableProducer(protocol.topic) + "_bridge)");
  }
  if (protocol.sensor_axes == "magnetometer") {
    q_body_sensor = mountings.q_body_magnetometer;
  } else if (!protocol.sensor_axes.empty()) {
    r.problem("protocol", "'" + file + "' gives sensor_axes '" + protocol.sensor_axes +
                              "': the mountings a frame's axes may name are: magnetometer (none: body axes)");
  }
  std::string why;
  if (const auto found = FrameMapping::of(protocol.frame, leafNames(*leaves), why)) {
    mapping = *found;
  } else {
    r.problem("protocol", "'" + file + "': " + why);
  }
  if (protocol.command) {
    const std::string allowed = actuatorCommandTopic(producer);
    if (protocol.command_topic != allowed) {
      return r.problem("protocol", "'" + file + "' takes commands from " + protocol.command_topic + ": " +
                                       (allowed.empty() ? producer + "'s device reports only (no actuator reports as " +
                                                              protocol.topic + ")"
                                                        : "the actuator reporting as " + protocol.topic + " takes " + allowed));
    }
    if (const auto found = FrameMapping::of(*protocol.command, leafNames(*bridgeableLeaves(allowed)), why)) {
      command_mapping = *found;
    } else {
      r.problem("protocol", "'" + file + "': command: " + why);
    }
  }
  if (baud) protocol.line.baud = *baud;
  r.problems(protocol.line.validate());
}

DeviceBridgeNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                  const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  DeviceBridgeNodeParams p;
  auto r = scenario.componentParams(args.name, problems);
  refuseDeviceKeys(r);
  // Flight software's belief of the mounting: what a bridge on the flight side knows.
  readProtocol(scenario, args.name, vehicle.onboard.sensors, r, problems, p.protocol, p.mapping, p.command_mapping,
               p.bridge.q_body_sensor);
  p.device = defaultDevicePath(args, p.protocol.name.empty() ? producerOf(args.name) : p.protocol.name);
  r.read("device", p.device);
  // Three periods of a slow device unsent before it is late; never sooner than 0.5 s.
  if (p.protocol.rate_hz) p.late_after_s = std::max(p.late_after_s, 3.0 / *p.protocol.rate_hz);
  r.read("late_after_s", p.late_after_s, "s");
  if (!(p.late_after_s > 0.0 && std::isfinite(p.late_after_s))) r.problem("late_after_s", "must be > 0");
  r.problems(p.bridge.validate());
  r.finish();
  return p;
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<DeviceBridgeNode>(argc, argv, "magnetometer_bridge", vehicle::withVehicle(readParams),
                                          bus::kBridgeStrength);
}

}  // namespace flatsat::device_bridge
