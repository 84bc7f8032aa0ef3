// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <cstdint>
#include <optional>
#include <random>
#include <chrono>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "bus/Node.hpp"
#include "bus/NodeMain.hpp"
#include "components/device_bridge/DeviceBridge.hpp"
#include "components/device_protocol/DeviceProtocol.hpp"
#include "components/device_sim/ReactionWheelDevice.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::device_sim {

/// Where each published field of a device's topic comes from in the truth.
struct TruthSource {
  std::size_t topic_leaf = 0;  // index into the topic's leaves
  std::size_t truth_leaf = 0;  // the truth's leaf of the same name
  double noise = 0.0;          // [topic unit] 1σ white noise, >= 0
};

struct DeviceSimParams {
  device_bridge::DeviceBridgeParams mounting;  // how the device sits in the body (as built: the truth's)
  device_protocol::DeviceProtocol protocol;    // its frame, line and topic (deploy/devices/*.yaml)
  device_bridge::FrameMapping mapping;         // where its frame carries the topic's fields
  std::vector<TruthSource> sources;            // every published field but `valid`
  std::size_t topic_leaves = 0;                // [-] how many leaves the topic has
  std::optional<std::size_t> valid_leaf;       // the topic's `valid`: 1, or 0 out of the field of view
  bool valid_in_frame = false;                 // the frame carries `valid` (else an invalid sample sends nothing)
  /// A Sun sensor head: the Sun is measured only within this cone about the boresight and
  /// out of eclipse; elsewhere the device says invalid and sends a zero vector.
  std::optional<double> fov_half_angle_rad;    // [rad] (0, π/2]
  Eigen::Vector3d boresight_B = Eigen::Vector3d::UnitX();  // [-] unit, body axes
  std::uint32_t truth_divider = 1; // [-] one frame every this many truth (or topic) samples, >= 1
  double corrupt_fraction = 0.0;   // [-] share of frames sent corrupted (bad check, garbage, cut), 0..1
  std::string link;                // pseudo-terminal slave path published as this symlink
  std::string port;                // a real serial port to send on instead ("" : a pseudo-terminal at `link`)
  std::uint64_t seed = 1;          // [-] noise and corruption
  /// truth: an ideal device measuring the truth (noise added); bus: the samples the
  /// topic's emulator publishes, framed as the device would send them (a flight
  /// computer's side of the line, its sensors emulated by the rig).
  std::string source = "truth";
  /// A reaction wheel (a description with a command frame): the unit's drive and rotors.
  /// Its frames report the rotors' own speeds, which its commands change.
  std::optional<ReactionWheelDeviceParams> wheel;
  std::optional<device_bridge::FrameMapping> command_mapping;  // where a command frame carries the command topic's fields
  std::array<std::size_t, 4> speed_leaves{};    // the topic's wheel_speed_rad_s[i]
  std::array<std::size_t, 4> torque_leaves{};   // the command topic's torque_Nm[i]
  double step_period_s = 0.1;                   // [s] the truth's period: the unit's clock between samples
};

/// Device simulator: plays a described device's end of a serial line on a pseudo-terminal,
/// for its bridge (or a flight computer) to read in place of a real unit on /dev/ttyUSB*.
/// It measures the truth (flatsat/truth: each published field is the truth's field of the
/// same name, plus white noise), or takes the emulator's samples of its topic
/// (`source: bus`), and sends the frames its description gives (deploy/devices/*.yaml), in
/// the device's axes, clipped at full scale; a share of them corrupted on purpose to
/// exercise the parser. A reaction wheel also reads command frames off the line and
/// reports its rotors' speeds (ReactionWheelDevice), periodically or one frame in answer
/// to each command (the description's `reply`), on the truth's clock.
class DeviceSimNode final : public bus::Node {
 public:
  DeviceSimNode(bus::Bus& bus, bus::NodeOptions options, const DeviceSimParams& params);
  ~DeviceSimNode() override;
  void run();  // until SIGINT/SIGTERM

 private:
  void send(const std::vector<double>& topic_values);  // on a reader's thread
  void sendLocked(const std::vector<double>& topic_values);  // under send_mutex_
  /// The topic's values an ideal device measures, white noise added; a wheel's speeds its own.
  std::vector<double> measure(const msg::TruthState& truth, const Eigen::Vector4d* wheel_speeds);
  void onTruth(const msg::TruthState& truth);                          // on the truth reader's thread
  void onCommand(const device_protocol::RawValues& frame);             // on run()'s thread
  /// The unit's clock: the newest truth time plus the wall time since it, up to a period.
  double deviceTime() const;
  /// The emulator's samples of the description's topic (source: bus), framed as they come.
  std::shared_ptr<void> subscribeTopic(bus::Bus& bus);

  DeviceSimParams params_;
  int master_ = -1, slave_ = -1;
  std::mt19937_64 random_;
  std::uint32_t sequence_ = 0;
  std::vector<std::size_t> measured_bytes_;  // offsets of the published fields' bytes: where a bit flips
  std::uint64_t truth_seen_ = 0, seen_ = 0;  // truth samples, topic samples
  std::atomic<std::uint64_t> sent_{0}, corrupted_{0}, dropped_{0}, refused_{0};
  std::optional<ReactionWheelDevice> wheel_;                  // guarded by send_mutex_
  std::optional<device_protocol::FrameParser> command_parser_;
  std::optional<device_bridge::DeviceBridge> command_decoder_;
  std::optional<msg::TruthState> last_truth_;                 // guarded by send_mutex_
  std::chrono::steady_clock::time_point last_truth_seen_;     // guarded by send_mutex_
  std::atomic<std::uint64_t> commands_{0};
  std::mutex send_mutex_;  // truth and topic samples come on their readers' threads
  std::unique_ptr<bus::ReaderOf<bus::topics::kTruth>> truth_;
  std::shared_ptr<void> topic_reader_;
};

DeviceSimParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle, const bus::NodeArgs& args,
                           bus::ConfigProblems& problems);

}  // namespace flatsat::device_sim
