// SPDX-License-Identifier: Apache-2.0
#include "components/device_sim/DeviceSimNode.hpp"

#include <fcntl.h>
#include <poll.h>
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
#include "bus/Stamp.hpp"
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

/// Each field the frame carries measured from the truth's field of the same name, with
/// noise: {<topic field>: 1σ in its unit}.
void readTruthSources(const std::vector<msg::FieldInfo>& leaves, bus::ParamReader& r, DeviceSimParams& p) {
  const auto& truth_leaves = msg::leafFields<msg::TruthState>();
  auto noise = r.section("noise");
  std::set<std::string> noisy;
  for (const auto& leaf : p.mapping.leaves) {
    const std::string name(leaves[leaf.leaf].name);
    if (name == "valid") continue;
    const auto truth_leaf = leafIndex(truth_leaves, name);
    if (!truth_leaf) {
      r.problem("protocol", "'" + p.protocol.file + "' carries '" + name +
                                "', which the truth does not: a device simulator cannot measure it");
      continue;
    }
    const std::string field = name.substr(0, name.find('['));
    double sigma = 0.0;
    noise.read(field, sigma, std::string(leaves[leaf.leaf].unit));
    if (!(sigma >= 0.0 && std::isfinite(sigma)) && noisy.insert(field).second) noise.problem(field, "must be >= 0");
    p.sources.push_back({leaf.leaf, *truth_leaf, sigma});
  }
  noise.finish();
}

/// An actuator's stand-in: a reaction wheel unit (the only actuator a description may
/// describe: device_bridge::actuatorCommandTopic), its rotors the truth's as built.
void readWheel(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle, const std::vector<msg::FieldInfo>& leaves,
               bus::ParamReader& r, DeviceSimParams& p) {
  if (p.source != "truth") {
    return r.problem("source", "a reaction wheel unit reports its own rotors' speeds: its source is truth (its clock and start)");
  }
  const auto& body = vehicle.truth.body;
  ReactionWheelDeviceParams wheel;
  wheel.wheel_count = body.wheel_count;
  wheel.inertia_kg_m2 = body.wheel_inertia_kg_m2;
  wheel.max_torque_Nm = body.wheel_count > 0 ? body.wheel_max_torque_Nm.head(body.wheel_count).minCoeff() : 0.0;
  r.read("max_torque_Nm", wheel.max_torque_Nm, "N m");
  r.read("response_delay_s", wheel.response_delay_s, "s");
  if (body.wheel_count < 1) return r.problem("protocol", "a reaction wheel unit needs the spacecraft's wheels (spacecraft.wheels)");
  r.problems(wheel.validate());
  const auto* command_leaves = device_bridge::bridgeableLeaves(p.protocol.command_topic);
  for (std::size_t i = 0; i < 4; ++i) {
    const std::string k = "[" + std::to_string(i) + "]";
    const auto speed = leafIndex(leaves, "wheel_speed_rad_s" + k);
    const auto torque = leafIndex(*command_leaves, "torque_Nm" + k);
    if (!speed || !torque) return r.problem("protocol", "'" + p.protocol.file + "': a reaction wheel reports wheel_speed_rad_s and takes torque_Nm");
    p.speed_leaves[i] = *speed;
    p.torque_leaves[i] = *torque;
  }
  p.step_period_s = scenario.step_s;
  p.wheel = wheel;
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
               params.wheel ? std::string("unit's own rotors, commanded on the line")
               : params.source == "bus" ? "emulator's " + params.protocol.topic : std::string("truth"));
  if (params.wheel) {
    wheel_.emplace(*params.wheel);
    command_parser_.emplace(*params.protocol.command);
    command_decoder_.emplace(params.mounting, *params.command_mapping);
  }
  // Readers last: their callbacks use the line.
  if (params.source == "bus") {
    topic_reader_ = subscribeTopic(bus);
  } else {
    truth_ = std::make_unique<bus::ReaderOf<bus::topics::kTruth>>(bus, bus::topics::kTruth, [this](const msg::TruthState& t) {
      if (wheel_) return onTruth(t);
      if (truth_seen_++ % params_.truth_divider == 0) send(measure(t, nullptr));
    });
  }
}

std::shared_ptr<void> DeviceSimNode::subscribeTopic(bus::Bus& bus) {
  std::shared_ptr<void> reader;
  device_bridge::withBridgeableTopic(params_.protocol.topic, [&](const auto& def) {
    using Def = std::remove_cvref_t<decltype(def)>;
    using Sample = typename Def::Type;
    reader = std::shared_ptr<bus::Reader<Def>>(new bus::Reader<Def>(bus, def, [this, producer = std::string(def.producer)](const Sample& sample) {
      // The emulator's samples only: a bridge of the same topic in the rig publishes this
      // line's own frames back, which framed again would go round for ever.
      if (bus::text(sample.header().source()) != producer) return;
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
  // No reader callback may write to the line once it is closed.
  truth_.reset();
  topic_reader_.reset();
  std::error_code ignored;
  if (params_.port.empty()) std::filesystem::remove(params_.link, ignored);
  if (slave_ >= 0) ::close(slave_);
  if (master_ >= 0) ::close(master_);
}

void DeviceSimNode::onTruth(const msg::TruthState& truth) {
  std::lock_guard lock(send_mutex_);
  const double t = static_cast<double>(truth.header().sim_time_ns()) * 1e-9;
  if (!last_truth_) wheel_->reset(bus::vec4(truth.wheel_speed_rad_s()), t);
  last_truth_ = truth;
  last_truth_seen_ = std::chrono::steady_clock::now();
  const Eigen::Vector4d speeds = wheel_->step(t);
  if (params_.protocol.reply == device_protocol::ReplyMode::kPeriodic && truth_seen_++ % params_.truth_divider == 0) {
    sendLocked(measure(truth, &speeds));
  }
}

double DeviceSimNode::deviceTime() const {
  const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_truth_seen_).count();
  return static_cast<double>(last_truth_->header().sim_time_ns()) * 1e-9 + std::clamp(since, 0.0, params_.step_period_s);
}

void DeviceSimNode::onCommand(const device_protocol::RawValues& frame) {
  const auto decoded = command_decoder_->step(frame);
  Eigen::Vector4d torque = Eigen::Vector4d::Zero();
  for (const auto& [leaf, value] : decoded.leaves) {
    for (int i = 0; i < 4; ++i) {
      if (leaf == params_.torque_leaves[static_cast<std::size_t>(i)]) torque(i) = value;
    }
  }
  std::lock_guard lock(send_mutex_);
  if (!last_truth_) return;  // the rig has not started: the unit is not powered
  const double t = deviceTime();
  if (!wheel_->command(torque, t)) {
    ++refused_;
    return;
  }
  ++commands_;
  if (params_.protocol.reply == device_protocol::ReplyMode::kPerCommand) {
    const Eigen::Vector4d speeds = wheel_->step(t);
    sendLocked(measure(*last_truth_, &speeds));
  }
}

std::vector<double> DeviceSimNode::measure(const msg::TruthState& truth, const Eigen::Vector4d* wheel_speeds) {
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
    values[source.topic_leaf] = msg::leafValue(truth, source.truth_leaf).value_or(0.0);
  }
  for (std::size_t i = 0; wheel_speeds != nullptr && i < 4; ++i) {
    values[params_.speed_leaves[i]] = (*wheel_speeds)(static_cast<Eigen::Index>(i));
  }
  for (const auto& source : params_.sources) {
    if (source.noise > 0.0) values[source.topic_leaf] += std::normal_distribution<double>(0.0, source.noise)(random_);
  }
  return values;
}

void DeviceSimNode::send(const std::vector<double>& topic_values) {
  std::lock_guard lock(send_mutex_);
  sendLocked(topic_values);
}

void DeviceSimNode::sendLocked(const std::vector<double>& topic_values) {
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
  const auto counters = [&] {
    std::string line = "frames sent " + std::to_string(sent_) + ", corrupted " + std::to_string(corrupted_) +
                       ", dropped " + std::to_string(dropped_) + ", refused " + std::to_string(refused_);
    if (!command_parser_) return line;
    const auto& c = command_parser_->counts();
    return line + "; cmds " + std::to_string(commands_) + ", bad " + std::to_string(c.bad_checksum + c.bad_header + c.bad_value);
  };
  using Clock = std::chrono::steady_clock;
  auto next_health = Clock::now() + std::chrono::seconds(1);
  std::array<std::uint8_t, 256> buffer{};
  while (!interrupted()) {
    if (!command_parser_) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    } else {
      // A unit that takes commands: whatever the other end writes, parsed as it comes.
      pollfd p{master_, POLLIN, 0};
      if (::poll(&p, 1, 100) > 0 && (p.revents & POLLIN)) {
        const ssize_t n = ::read(master_, buffer.data(), buffer.size());
        for (ssize_t i = 0; i < n; ++i) {
          if (const auto frame = command_parser_->push(buffer[static_cast<std::size_t>(i)])) onCommand(*frame);
        }
      }
    }
    if (Clock::now() >= next_health) {
      publishHealth(msg::ComponentState::RUNNING, sent_, counters());
      next_health = Clock::now() + std::chrono::seconds(1);
    }
  }
  publishHealth(msg::ComponentState::STOPPED, sent_, "stopped; " + counters());
}

DeviceSimParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle, const bus::NodeArgs& args,
                           bus::ConfigProblems& problems) {
  DeviceSimParams p;
  p.seed = scenario.seedFor(args.name);
  auto r = scenario.componentParams(args.name, problems);
  device_bridge::refuseDeviceKeys(r);
  // The unit as it sits (the truth's mounting), not as flight software believes it sits.
  device_bridge::readProtocol(scenario, args.name, vehicle.truth.sensors, r, problems, p.protocol, p.mapping, p.command_mapping,
                              p.mounting.q_body_sensor);
  p.link = device_bridge::defaultDevicePath(args, p.protocol.name);
  r.read("link", p.link);
  r.read("port", p.port);
  r.read("source", p.source);
  if (p.source != "truth" && p.source != "bus") r.problem("source", "'" + p.source + "' is neither truth nor bus");
  // A device with a rate of its own sends one frame in as many truth samples as fit its
  // period (on the bus it frames the emulator's samples as they come, at the emulator's rate).
  if (p.protocol.rate_hz && p.source == "truth") {
    p.truth_divider = static_cast<std::uint32_t>(std::max(1.0, std::round(1.0 / (scenario.step_s * *p.protocol.rate_hz))));
  }
  r.read("truth_divider", p.truth_divider);
  r.read("corrupt_fraction", p.corrupt_fraction, "-");
  if (p.truth_divider < 1) r.problem("truth_divider", "must be >= 1");
  if (!(p.corrupt_fraction >= 0.0 && p.corrupt_fraction <= 1.0)) r.problem("corrupt_fraction", "must be in 0..1");
  const auto leaves = device_bridge::bridgeableLeaves(p.protocol.topic);
  if (leaves) {
    p.topic_leaves = leaves->size();
    p.valid_leaf = leafIndex(*leaves, "valid");
    p.valid_in_frame = p.valid_leaf && std::any_of(p.mapping.leaves.begin(), p.mapping.leaves.end(),
                                                   [&](const auto& leaf) { return leaf.leaf == *p.valid_leaf; });
    if (p.source == "bus") {
      // The emulator's sample has every field, with its own noise.
      if (r.has("noise")) r.problem("noise", "the emulator's samples carry their own noise (source: bus): the stand-in adds none");
      r.leave({"noise"});
    } else {
      readTruthSources(*leaves, r, p);
    }
  }
  if (p.protocol.topic == bus::topics::kSunSensor.name) {
    p.fov_half_angle_rad = kSunHead.fov_half_angle_rad;
    r.read("fov_half_angle_rad", *p.fov_half_angle_rad, "rad");
    if (!(*p.fov_half_angle_rad > 0.0 && *p.fov_half_angle_rad <= M_PI / 2)) {
      r.problem("fov_half_angle_rad", "must be in (0, 90 deg]");
    }
    p.boresight_B = vehicle.truth.sensors.sun_sensor_boresight_B;
  }
  if (p.command_mapping && leaves) readWheel(scenario, vehicle, *leaves, r, p);
  r.problems(p.mounting.validate());
  r.finish();
  return p;
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<DeviceSimNode>(argc, argv, "magnetometer_device", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::device_sim
