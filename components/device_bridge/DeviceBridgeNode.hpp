// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "bus/Node.hpp"
#include "bus/NodeMain.hpp"
#include "components/device_bridge/DeviceBridge.hpp"
#include "components/device_protocol/DeviceProtocol.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::device_bridge {

class SerialPort;

struct DeviceBridgeNodeParams {
  DeviceBridgeParams bridge;
  device_protocol::DeviceProtocol protocol;  // the device's frame, line and topic (deploy/devices/*.yaml)
  FrameMapping mapping;                      // where its frame carries the topic's fields
  std::optional<FrameMapping> command_mapping;  // an actuator's: where its command frame carries the command topic's
  std::string device;  // serial port or pseudo-terminal (default: <run dir>/<device name>.pty)
  double late_after_s = 0.5;  // [s] no good frame for this long: late (health, a warning), > 0; below the lease (1 s)
};

/// Hardware bridge (architecture, "Hardware swap-in"), for any device a description gives
/// (docs/devices.md): frames from the device's serial line out on the description's topic
/// at the bridge ownership strength, so its samples win over the emulator's while it lives;
/// when it dies its liveliness lease runs out and readers fall back to the emulator. Not
/// stepped: each sample is stamped with the step of its arrival (stepNow()). Bad frames are
/// counted (health) and never published. A device that falls silent is `late` (health, a
/// warning) after late_after_s, and then, writing nothing, loses its lease like a dead bridge.
/// An actuator's bridge (a description with a command frame) also takes its command topic
/// and writes each sample to the device as a command frame, in the device's axes.
class DeviceBridgeNode final : public bus::Node {
 public:
  DeviceBridgeNode(bus::Bus& bus, bus::NodeOptions options, const DeviceBridgeNodeParams& params);
  ~DeviceBridgeNode() override;

  /// Until SIGINT/SIGTERM; throws NodeFailure when the line is lost.
  void run();

 private:
  /// The step a sample arriving now belongs to: the newest grant plus the whole
  /// periods since it, rounded (a frame may come just before its step's grant).
  /// None before the first grant.
  std::optional<bus::StepContext> stepNow() const;
  std::string counters() const;
  std::function<bool(const BridgeSample&, const bus::StepContext&)> publisherFor(const std::string& topic);
  /// The command topic's reader for an actuator (null for a sensor): each sample to the line.
  std::shared_ptr<void> subscribeCommands(bus::Bus& bus);
  void writeCommand(const std::vector<double>& command_values, std::uint64_t step);  // on the reader's thread
  /// The stamp of a frame arriving now: stepNow(), or for a unit that answers each
  /// command, the step after the command's.
  std::optional<bus::StepContext> stampFor() const;

  DeviceBridgeNodeParams params_;
  DeviceBridge bridge_;
  device_protocol::FrameParser parser_;
  std::uint64_t missed_ = 0;
  std::uint64_t unrepresentable_ = 0;  // a value its topic field cannot hold (setLeaf refused it)
  /// Writes one sample on the description's topic; false: a value its field cannot hold.
  std::function<bool(const BridgeSample&, const bus::StepContext&)> publish_;
  struct Grant {
    bus::StepContext step;
    std::chrono::steady_clock::time_point seen;
  };
  mutable std::mutex grant_mutex_;
  std::optional<Grant> grant_;
  std::atomic<bool> run_ended_{false};  // the time master's last grant said stop
  bus::ReaderOf<bus::topics::kStepGrant> grants_;
  mutable std::mutex port_mutex_;
  std::optional<std::uint64_t> last_command_step_;  // guarded by port_mutex_
  std::unique_ptr<SerialPort> port_;  // open while run() runs; commands need it
  std::uint32_t command_sequence_ = 0;
  std::atomic<std::uint64_t> commands_sent_{0}, commands_unsent_{0}, commands_refused_{0};
  std::shared_ptr<void> commands_;  // last: its callback uses the members above
};

DeviceBridgeNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                  const bus::NodeArgs& args, bus::ConfigProblems& problems);

/// The pseudo-terminal path a bridge and its device simulator agree on by default:
/// <run dir>/<device>.pty, the device named as its description names it.
std::string defaultDevicePath(const bus::NodeArgs& args, const std::string& device_name);

/// The scenario key `protocol` (default: the shipped <producer>.yaml of the component
/// `<producer>_bridge` or `<producer>_device`) read and checked: a description whose
/// topic is the one that component stands for, with its mapping onto the topic's fields;
/// `baud` overrides its line rate. The mounting its sensor_axes names goes to `q_body_sensor`
/// from `mountings`. An actuator's command frame (its command topic the one
/// actuatorCommandTopic allows) is mapped into `command_mapping`. Problems go to `r` and `problems`.
void readProtocol(const bus::Scenario& scenario, const std::string& component, const vehicle::SensorMountings& mountings,
                  bus::ParamReader& r, bus::ConfigProblems& problems, device_protocol::DeviceProtocol& protocol,
                  FrameMapping& mapping, std::optional<FrameMapping>& command_mapping, Eigen::Quaterniond& q_body_sensor);

/// Refuses the keys that are no longer a bridge's or a device's (mounting, range), saying where they went.
void refuseDeviceKeys(bus::ParamReader& r);

}  // namespace flatsat::device_bridge
