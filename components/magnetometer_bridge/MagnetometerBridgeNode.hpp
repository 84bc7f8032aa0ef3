// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <chrono>
#include <mutex>
#include <optional>
#include <string>

#include "bus/Node.hpp"
#include "bus/NodeMain.hpp"
#include "components/device_protocol/DeviceProtocol.hpp"
#include "components/magnetometer_bridge/MagnetometerBridge.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::magnetometer_bridge {

struct MagnetometerBridgeNodeParams {
  MagnetometerBridgeParams bridge;
  device_protocol::DeviceProtocol protocol;  // the device's frame and line (deploy/devices/magnetometer.yaml)
  MagnetometerFields fields;                 // where its frame carries the field
  std::string device;  // serial port or pseudo-terminal (default: <run dir>/magnetometer.pty)
  double late_after_s = 0.5;  // [s] no good frame for this long: late (health, a warning), > 0; below the lease (1 s)
};

/// Hardware bridge (architecture, "Hardware swap-in"): frames from the device's serial line out
/// as flatsat/magnetometer at the bridge ownership strength, so its samples win
/// over the emulator's while it lives; when it dies its liveliness lease runs
/// out and readers fall back to the emulator. Not stepped: each sample is
/// stamped with the step of its arrival (stepNow()). Bad frames are counted (health)
/// and never published. A device that falls silent is `late` (health, a warning)
/// after late_after_s, and then, writing nothing, loses its lease like a dead bridge.
class MagnetometerBridgeNode final : public bus::Node {
 public:
  MagnetometerBridgeNode(bus::Bus& bus, bus::NodeOptions options,
                         const MagnetometerBridgeNodeParams& params);

  /// Until SIGINT/SIGTERM; throws NodeFailure when the line is lost.
  void run();

 private:
  MagnetometerBridgeNodeParams params_;
  MagnetometerBridge bridge_;
  device_protocol::FrameParser parser_;
  std::uint64_t missed_ = 0;
  /// The step a sample arriving now belongs to: the newest grant plus the whole
  /// periods since it, rounded (a frame may come just before its step's grant).
  /// None before the first grant.
  std::optional<bus::StepContext> stepNow() const;
  struct Grant {
    bus::StepContext step;
    std::chrono::steady_clock::time_point seen;
  };
  mutable std::mutex grant_mutex_;
  std::optional<Grant> grant_;
  bus::ReaderOf<bus::topics::kStepGrant> grants_;
  bus::WriterOf<bus::topics::kMagnetometer>& reading_ = addOutput(bus::topics::kMagnetometer);
};

MagnetometerBridgeNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                        const bus::NodeArgs& args, bus::ConfigProblems& problems);

/// The pseudo-terminal path bridge and device simulator agree on by default.
std::string defaultDevicePath(const bus::NodeArgs& args);

/// The scenario key `protocol` (default: the shipped magnetometer.yaml) read and checked
/// as a magnetometer's description: frames on flatsat/magnetometer carrying b_body_T;
/// `baud` overrides its line rate. Problems go to `r` and `problems`.
void readMagnetometerProtocol(const bus::Scenario& scenario, bus::ParamReader& r, bus::ConfigProblems& problems,
                              device_protocol::DeviceProtocol& protocol, MagnetometerFields& fields);

}  // namespace flatsat::magnetometer_bridge
