// SPDX-License-Identifier: Apache-2.0
#include "components/device_sim/DeviceSimNode.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <thread>

#include <spdlog/spdlog.h>

#include "bus/Convert.hpp"
#include "components/Processes.hpp"
#include "components/device_bridge/BridgeableTopics.hpp"
#include "components/device_bridge/DeviceBridgeNode.hpp"
#include "components/device_bridge/SerialPort.hpp"
#include "components/sun_sensor/SunSensorModel.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::device_sim {
namespace {

/// The Sun sensor emulator's head: its field of view and the Sun fraction it needs.
const sun_sensor::SunSensorParams kSunHead{};

std::optional<std::size_t> leafIndex(const std::vector<msg::FieldInfo>& leaves, const std::string& name) {
  const auto it = std::find_if(leaves.begin(), leaves.end(), [&](const msg::FieldInfo& f) { return f.name == name; });
  if (it == leaves.end()) return std::nullopt;
  return static_cast<std::size_t>(it - leaves.begin());
}

}  // namespace

DeviceSimNode::DeviceSimNode(bus::Bus& bus, bus::NodeOptions options, const DeviceSimParams& params)
    : Node(bus, std::move(options)),
      params_(params),
      random_(params.seed) {
  if (!params.port.empty()) {
    // A real line: the frames go out of a serial port to whatever listens (a flight computer).
    master_ = ::open(params.port.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (master_ < 0) throw std::runtime_error(params.port + ": cannot open: " + std::strerror(errno));
    device_bridge::makeRaw(master_, params.protocol.line, params.port);
    spdlog::info("{}: {} on {} at {} baud", name(), params.protocol.name, params.port, params.protocol.line.baud);
  } else {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0) {
      throw std::runtime_error("cannot open a pseudo-terminal: " + std::string(std::strerror(errno)));
    }
    const std::string slave = ::ptsname(master_);
    // Held open so the line exists (and stays raw) while no bridge listens.
    slave_ = ::open(slave.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (slave_ < 0) throw std::runtime_error(slave + ": cannot open: " + std::strerror(errno));
    device_bridge::makeRaw(slave_, params.protocol.line, slave);
    std::filesystem::remove(params.link);
    std::filesystem::create_symlink(slave, params.link);
    spdlog::info("{}: {} on {} (linked as {})", name(), params.protocol.name, slave, params.link);
  }
  for (const auto& field : params.protocol.frame.fields) {
    if (field.maps_to.empty()) continue;
    for (std::size_t b = field.at; b < field.end(); ++b) measured_bytes_.push_back(b);
  }
  spdlog::info("{}: frames from the {}", name(),
               params.source == "bus" ? "emulator's " + params.protocol.topic : std::string("truth"));
  // Readers last: their callbacks use the line.
  if (params.source == "bus") {
    topic_reader_ = subscribeTopic(bus);
  } else {
    truth_ = std::make_unique<bus::ReaderOf<bus::topics::kTruth>>(bus, bus::topics::kTruth, [this](const msg::TruthState& t) {
      if (truth_seen_++ % params_.truth_divider == 0) send(measure(t));
    });
  }
}

std::shared_ptr<void> DeviceSimNode::subscribeTopic(bus::Bus& bus) {
  std::shared_ptr<void> reader;
  device_bridge::withBridgeableTopic(params_.protocol.topic, [&](const auto& def) {
    using Def = std::remove_cvref_t<decltype(def)>;
    using Sample = typename Def::Type;
    reader = std::shared_ptr<bus::Reader<Def>>(new bus::Reader<Def>(bus, def, [this](const Sample& sample) {
      std::vector<double> values(params_.topic_leaves, 0.0);
      for (std::size_t i = 0; i < values.size(); ++i) {
        values[i] = msg::leafValue(sample, i).value_or(0.0);
        // What arrives on the bus is checked, not trusted: a NaN never reaches the line.
        if (!std::isfinite(values[i])) {
          ++refused_;
          return;
        }
      }
      // A sample the emulator marks invalid is a dropout: a device whose frame has no
      // valid flag sends nothing then.
      const bool valid = !params_.valid_leaf || values[*params_.valid_leaf] != 0.0;
      if (!valid && !params_.valid_in_frame) return;
      if (seen_++ % params_.truth_divider == 0) send(values);
    }, {}, {}, trustFor(def)));
  });
  return reader;
}

DeviceSimNode::~DeviceSimNode() {
  std::error_code ignored;
  if (params_.port.empty()) std::filesystem::remove(params_.link, ignored);
  if (slave_ >= 0) ::close(slave_);
  if (master_ >= 0) ::close(master_);
}

std::vector<double> DeviceSimNode::measure(const msg::TruthState& truth) {
  std::vector<double> values(params_.topic_leaves, 0.0);
  bool valid = true;
  if (params_.fov_half_angle_rad) {
    const Eigen::Vector3d sun_B = bus::vec3(truth.sun_body_unit());
    valid = truth.illumination() >= kSunHead.min_illumination &&
            sun_B.normalized().dot(params_.boresight_B) >= std::cos(*params_.fov_half_angle_rad);
  }
  if (params_.valid_leaf) values[*params_.valid_leaf] = valid ? 1.0 : 0.0;
  if (!valid) return values;  // an invalid measurement carries zeros
  for (const auto& source : params_.sources) {
    std::normal_distribution<double> noise(0.0, source.noise);
    values[source.topic_leaf] =
        msg::leafValue(truth, source.truth_leaf).value_or(0.0) + (source.noise > 0.0 ? noise(random_) : 0.0);
  }
  return values;
}

void DeviceSimNode::send(const std::vector<double>& topic_values) {
  std::lock_guard lock(send_mutex_);
  const auto& spec = params_.protocol.frame;
  auto frame = device_protocol::encodeFrame(
      spec, device_bridge::deviceFrame(topic_values, params_.mounting, spec, params_.mapping, sequence_++));
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

void DeviceSimNode::run() {
  publishHealth(msg::ComponentState::RUNNING, 0, "device on " + (params_.port.empty() ? params_.link : params_.port));
  while (!interrupted()) {
    std::this_thread::sleep_for(std::chrono::seconds(1));
    publishHealth(msg::ComponentState::RUNNING, sent_,
                  "frames sent " + std::to_string(sent_) + ", corrupted " + std::to_string(corrupted_) +
                      ", dropped " + std::to_string(dropped_) + ", refused " + std::to_string(refused_));
  }
  publishHealth(msg::ComponentState::STOPPED, sent_, "stopped");
}

DeviceSimParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle, const bus::NodeArgs& args,
                           bus::ConfigProblems& problems) {
  DeviceSimParams p;
  p.seed = scenario.seedFor(args.name);
  auto r = scenario.componentParams(args.name, problems);
  device_bridge::refuseDeviceKeys(r);
  // The unit as it sits (the truth's mounting), not as flight software believes it sits.
  device_bridge::readProtocol(scenario, args.name, vehicle.truth.sensors, r, problems, p.protocol, p.mapping,
                              p.mounting.q_body_sensor);
  p.link = device_bridge::defaultDevicePath(args, p.protocol.name);
  r.read("link", p.link);
  r.read("port", p.port);
  r.read("source", p.source);
  if (p.source != "truth" && p.source != "bus") r.problem("source", "'" + p.source + "' is neither truth nor bus");
  r.read("truth_divider", p.truth_divider);
  r.read("corrupt_fraction", p.corrupt_fraction, "-");
  if (p.truth_divider < 1) r.problem("truth_divider", "must be >= 1");
  if (!(p.corrupt_fraction >= 0.0 && p.corrupt_fraction <= 1.0)) r.problem("corrupt_fraction", "must be in 0..1");
  const auto leaves = device_bridge::bridgeableLeaves(p.protocol.topic);
  if (leaves) {
    const auto& truth_leaves = msg::leafFields<msg::TruthState>();
    p.topic_leaves = leaves->size();
    p.valid_leaf = leafIndex(*leaves, "valid");
    p.valid_in_frame = p.valid_leaf && std::any_of(p.mapping.leaves.begin(), p.mapping.leaves.end(),
                                                   [&](const auto& leaf) { return leaf.leaf == *p.valid_leaf; });
    // noise: {<topic field>: 1σ in its unit}, for the fields the frame carries.
    auto noise = r.section("noise");
    std::set<std::string> noisy;
    for (const auto& leaf : p.mapping.leaves) {
      const std::string name((*leaves)[leaf.leaf].name);
      if (name == "valid") continue;
      const auto truth_leaf = leafIndex(truth_leaves, name);
      if (p.source == "bus") continue;  // the emulator's sample has every field
      if (!truth_leaf) {
        r.problem("protocol", "'" + p.protocol.file + "' carries '" + name +
                                  "', which the truth does not: a device simulator cannot measure it");
        continue;
      }
      const std::string field = name.substr(0, name.find('['));
      double sigma = 0.0;
      noise.read(field, sigma, std::string((*leaves)[leaf.leaf].unit));
      if (!(sigma >= 0.0 && std::isfinite(sigma)) && noisy.insert(field).second) noise.problem(field, "must be >= 0");
      p.sources.push_back({leaf.leaf, *truth_leaf, sigma});
    }
    noise.finish();
  }
  if (p.protocol.topic == bus::topics::kSunSensor.name) {
    p.fov_half_angle_rad = kSunHead.fov_half_angle_rad;
    r.read("fov_half_angle_rad", *p.fov_half_angle_rad, "rad");
    if (!(*p.fov_half_angle_rad > 0.0 && *p.fov_half_angle_rad <= M_PI / 2)) {
      r.problem("fov_half_angle_rad", "must be in (0, 90 deg]");
    }
    p.boresight_B = vehicle.truth.sensors.sun_sensor_boresight_B;
  }
  r.problems(p.mounting.validate());
  r.finish();
  return p;
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<DeviceSimNode>(argc, argv, "magnetometer_device", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::device_sim
