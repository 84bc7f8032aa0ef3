// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bus/Params.hpp"
#include "components/device_protocol/FrameSpec.hpp"

namespace flatsat::device_protocol {

/// The serial line a device speaks on.
struct LineSettings {
  std::uint32_t baud = 115200;  // [bit/s] a standard rate, 1200..921600
  int data_bits = 8;            // [-] 8: binary frames need every bit
  std::string parity = "none";  // none | even | odd
  int stop_bits = 1;            // [-] 1 or 2

  /// Every violation as "key: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// When a device sends its frame.
enum class ReplyMode {
  kPeriodic,    // at its own rate (a sensor streaming)
  kPerCommand,  // one frame in answer to each command frame (request/response)
};

/// A device's protocol as its description file gives it (deploy/devices/*.yaml,
/// docs/devices.md): the line, the topic its frames carry, and the frame; for an
/// actuator also the topic whose samples it takes as command frames.
struct DeviceProtocol {
  std::string file;         // where it was read from
  std::string name;         // the device, e.g. "magnetometer"
  std::string topic;        // the bus topic its readings map onto, e.g. "flatsat/magnetometer"
  std::string sensor_axes;  // vectors arrive in this mounting's axes (spacecraft.sensors.<name>); "" : body
  LineSettings line;
  FrameSpec frame;          // what the device sends
  std::string command_topic;       // an actuator's command topic, e.g. "flatsat/wheel_torque_cmd"; "" : a sensor
  std::optional<FrameSpec> command;  // what the device takes (with command_topic)
  ReplyMode reply = ReplyMode::kPeriodic;
  /// [Hz] a periodic device's output rate, (0, 10000]; none: as fast as it is driven.
  /// The stand-in sends at it, the bridge is late after three of its periods unsent.
  std::optional<double> rate_hz;
};

/// The unit of a topic's field ("b_body_T[0]" → "T"), as bus::ParamReader spells units;
/// nullopt when the topic has no such field.
using FieldUnitLookup = std::function<std::optional<std::string>(const std::string& topic, const std::string& field)>;

/// The description file `name`: as given when absolute, else beside the scenario file,
/// else among the descriptions shipped with the rig (deploy/devices/, installed under
/// share/flatsat/devices/); `name` itself when none exists.
std::string findDeviceDescription(const std::string& scenario_file, const std::string& name);

/// Reads and checks a description. Every problem goes to `problems` as
/// "file:line:col: key: reason" (the field's own line for a field's problem); the
/// result is meaningful only when none was added.
DeviceProtocol readDeviceProtocol(const std::string& path, const FieldUnitLookup& unit_of, bus::ConfigProblems& problems);

}  // namespace flatsat::device_protocol
