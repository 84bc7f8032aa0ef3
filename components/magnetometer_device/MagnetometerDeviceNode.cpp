// SPDX-License-Identifier: Apache-2.0
#include "components/magnetometer_device/MagnetometerDeviceNode.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include <spdlog/spdlog.h>

#include "bus/Convert.hpp"
#include "components/Processes.hpp"
#include "components/magnetometer_bridge/MagnetometerBridgeNode.hpp"
#include "components/magnetometer_bridge/SerialPort.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::magnetometer_device {

MagnetometerDeviceNode::MagnetometerDeviceNode(bus::Bus& bus, bus::NodeOptions options,
                                               const MagnetometerDeviceParams& params)
    : Node(bus, std::move(options)),
      params_(params),
      random_(params.seed),
      truth_(bus, bus::topics::kTruth, [this](const msg::TruthState& t) { send(t); }) {
  master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0) {
    throw std::runtime_error("cannot open a pseudo-terminal: " + std::string(std::strerror(errno)));
  }
  const std::string slave = ::ptsname(master_);
  // Held open so the line exists (and stays raw) while no bridge listens.
  slave_ = ::open(slave.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave_ < 0) throw std::runtime_error(slave + ": cannot open: " + std::strerror(errno));
  magnetometer_bridge::makeRaw(slave_, params.protocol.line, slave);
  for (const auto& field : params.protocol.frame.fields) {
    if (field.maps_to.empty()) continue;
    for (std::size_t b = field.at; b < field.end(); ++b) measured_bytes_.push_back(b);
  }
  std::filesystem::remove(params.link);
  std::filesystem::create_symlink(slave, params.link);
  spdlog::info("{}: device on {} (linked as {})", name(), slave, params.link);
}

MagnetometerDeviceNode::~MagnetometerDeviceNode() {
  std::error_code ignored;
  std::filesystem::remove(params_.link, ignored);
  if (slave_ >= 0) ::close(slave_);
  if (master_ >= 0) ::close(master_);
}

void MagnetometerDeviceNode::send(const msg::TruthState& truth) {
  if (truth_seen_++ % params_.truth_divider != 0) return;
  std::normal_distribution<double> noise(0.0, params_.noise_T);
  Eigen::Vector3d b_B = bus::vec3(truth.b_body_T());
  if (params_.noise_T > 0.0) b_B += Eigen::Vector3d(noise(random_), noise(random_), noise(random_));
  const auto& spec = params_.protocol.frame;
  auto frame = device_protocol::encodeFrame(
      spec, magnetometer_bridge::deviceFrame(b_B, params_.mounting, spec, params_.fields, sequence_++));
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  if (uniform(random_) < params_.corrupt_fraction) {
    // One of three line faults: a flipped bit of a measurement (the check catches it),
    // noise with sync bytes in it before the frame (resynchronisation), a frame cut short.
    const int kind = static_cast<int>(uniform(random_) * 3);
    if (kind == 0) frame[measured_bytes_[static_cast<std::size_t>(uniform(random_) * measured_bytes_.size())]] ^= 0x10;
    if (kind == 1) {
      std::vector<std::uint8_t> garbage = {spec.sync.front(), 0x13};
      garbage.insert(garbage.end(), spec.sync.begin(), spec.sync.end());
      garbage.push_back(0x02);
      (void)!::write(master_, garbage.data(), garbage.size());
    }
    const std::size_t size = kind == 2 ? frame.size() / 2 : frame.size();
    (void)!::write(master_, frame.data(), size);
    ++corrupted_;
    return;
  }
  if (::write(master_, frame.data(), frame.size()) == static_cast<ssize_t>(frame.size())) {
    ++sent_;
  } else {
    ++dropped_;  // nobody reading and the line's buffer full, as a real UART overruns
  }
}

void MagnetometerDeviceNode::run() {
  publishHealth(msg::ComponentState::RUNNING, 0, "device on " + params_.link);
  while (!interrupted()) {
    std::this_thread::sleep_for(std::chrono::seconds(1));
    publishHealth(msg::ComponentState::RUNNING, sent_,
                  "frames sent " + std::to_string(sent_) + ", corrupted " + std::to_string(corrupted_) +
                      ", dropped " + std::to_string(dropped_));
  }
  publishHealth(msg::ComponentState::STOPPED, sent_, "stopped");
}

MagnetometerDeviceParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                    const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  MagnetometerDeviceParams p;
  p.mounting.q_body_sensor = vehicle.truth.sensors.q_body_magnetometer;  // as the unit sits
  p.link = magnetometer_bridge::defaultDevicePath(args);
  p.seed = scenario.seedFor(args.name);
  auto r = scenario.componentParams(args.name, problems);
  vehicle::refuseMovedKeys(r, {{"q_body_sensor", "spacecraft.sensors.magnetometer.q_body_sensor"}});
  r.read("link", p.link);
  magnetometer_bridge::readMagnetometerProtocol(scenario, r, problems, p.protocol, p.fields);
  r.read("range_T", p.mounting.range_T, "T");
  r.read("noise_T", p.noise_T, "T");
  r.read("truth_divider", p.truth_divider);
  r.read("corrupt_fraction", p.corrupt_fraction, "-");
  if (!(p.noise_T >= 0.0)) r.problem("noise_T", "must be >= 0");
  if (p.truth_divider < 1) r.problem("truth_divider", "must be >= 1");
  if (!(p.corrupt_fraction >= 0.0 && p.corrupt_fraction <= 1.0)) {
    r.problem("corrupt_fraction", "must be in 0..1");
  }
  r.problems(p.mounting.validate());
  r.finish();
  return p;
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<MagnetometerDeviceNode>(argc, argv, "magnetometer_device", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::magnetometer_device
