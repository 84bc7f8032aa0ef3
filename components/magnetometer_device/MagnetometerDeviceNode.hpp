// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <atomic>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "bus/Node.hpp"
#include "bus/NodeMain.hpp"
#include "components/device_protocol/DeviceProtocol.hpp"
#include "components/magnetometer_bridge/MagnetometerBridge.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::magnetometer_device {

struct MagnetometerDeviceParams {
  magnetometer_bridge::MagnetometerBridgeParams mounting;  // how the device sits in the body
  device_protocol::DeviceProtocol protocol;                // its frame and line (deploy/devices/magnetometer.yaml)
  magnetometer_bridge::MagnetometerFields fields;          // where its frame carries the field
  double noise_T = 0.0;            // [T] 1σ white noise per axis, >= 0
  std::uint32_t truth_divider = 1; // [-] one frame every this many truth samples, >= 1
  double corrupt_fraction = 0.0;   // [-] share of frames sent corrupted (bad check, garbage, cut), 0..1
  std::string link;                // pseudo-terminal slave path published as this symlink
  std::uint64_t seed = 1;          // [-] noise and corruption
};

/// Device simulator: plays the magnetometer's end of a serial line on a
/// pseudo-terminal, for the bridge to read in place of a real device on
/// /dev/ttyUSB*. It senses the truth field (flatsat/truth) and sends the frames
/// its description gives (deploy/devices/magnetometer.yaml); a share of them
/// corrupted on purpose to exercise the bridge's parser.
class MagnetometerDeviceNode final : public bus::Node {
 public:
  MagnetometerDeviceNode(bus::Bus& bus, bus::NodeOptions options, const MagnetometerDeviceParams& params);
  ~MagnetometerDeviceNode() override;
  void run();  // until SIGINT/SIGTERM

 private:
  void send(const msg::TruthState& truth);  // on the reader's thread

  MagnetometerDeviceParams params_;
  int master_ = -1, slave_ = -1;
  std::mt19937_64 random_;
  std::uint32_t sequence_ = 0;
  std::vector<std::size_t> measured_bytes_;  // offsets of the published fields' bytes: where a bit flips
  std::uint64_t truth_seen_ = 0;
  std::atomic<std::uint64_t> sent_{0}, corrupted_{0}, dropped_{0};
  bus::ReaderOf<bus::topics::kTruth> truth_;
};

MagnetometerDeviceParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                    const bus::NodeArgs& args, bus::ConfigProblems& problems);

}  // namespace flatsat::magnetometer_device
