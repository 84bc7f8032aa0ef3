// SPDX-License-Identifier: Apache-2.0
#include "tests/fuzz/FuzzTargets.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include "bus/GuardedType.hpp"
#include "bus/Scenario.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "components/common/FaultParams.hpp"
#include "components/device_protocol/DeviceProtocol.hpp"
#include "components/device_protocol/FrameCodec.hpp"
#include "components/unloading_controller/UnloadingControllerNode.hpp"

namespace flatsat::fuzz {

namespace {

/// A broken invariant: thrown, so libFuzzer records a crash and the replay
/// test a failure naming it.
void require(bool condition, const char* what) {
  if (!condition) throw std::logic_error(std::string("fuzz invariant broken: ") + what);
}

/// Decodes the bytes as the bus would; false when they do not decode.
template <class Def>
bool decode(const std::uint8_t* data, std::size_t size, typename Def::Type& sample) {
  bus::GuardedType<typename Def::PubSubType> type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(size));
  std::copy_n(data, size, payload.data);
  payload.length = static_cast<std::uint32_t>(size);
  return type.deserialize(&payload, &sample);
}

}  // namespace

void scenario(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/flatsat-fuzz-scenario-" + std::to_string(::getpid()) + ".yaml";
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    const auto s = bus::loadScenario(path);
    // [1 ms, 600 s]; a paced rig's at most 10 s (bus/Scenario.cpp, S3's minute steps).
    require(s.step_s >= 1e-3 && s.step_s <= 600.0, "accepted step_s out of range");
    require(s.pacing != bus::Pacing::kPaced || s.step_s <= 10.0, "accepted a paced step_s over 10 s");
    require((s.duration_s > 0) != (s.duration_orbits > 0), "accepted no single duration");
    for (const auto& c : s.components) {
      require(c.rate_divider >= 1 && c.rate_divider <= 1000, "accepted rate_divider out of range");
    }
  } catch (const bus::ScenarioError&) {
    // rejected with reasons: what must happen to bad input
  }
}

void magnetometerFrame(const std::uint8_t* data, std::size_t size) {
  static const device_protocol::FrameSpec spec = [] {
    bus::ConfigProblems problems;
    const auto any_field = [](const std::string&, const std::string&) { return std::optional<std::string>("T"); };
    const auto protocol = device_protocol::readDeviceProtocol(FLATSAT_MAGNETOMETER_DEVICE, any_field, problems);
    if (!problems.empty()) throw std::runtime_error(problems.joined());
    return protocol.frame;
  }();
  device_protocol::FrameParser parser(spec);
  for (std::size_t i = 0; i < size; ++i) {
    const auto values = parser.push(data[i]);
    if (!values) continue;
    require(i + 1 >= spec.size(), "a frame from fewer bytes than a frame");
    const auto frame = device_protocol::encodeFrame(spec, *values);
    require(std::equal(frame.begin(), frame.end(), data + i + 1 - spec.size()),
            "a delivered frame differs from the bytes it came from");
  }
}

void faultCommand(const std::uint8_t* data, std::size_t size) {
  msg::FaultCmd command;
  if (!decode<std::remove_cvref_t<decltype(bus::topics::kFaultCmd)>>(data, size, command)) return;
  constexpr int kChannels = 3;
  SensorFault fault;
  if (!toSensorFault(command, kChannels, fault).empty()) return;  // refused with reasons
  require(fault.channel >= -1 && fault.channel < kChannels, "accepted a channel out of range");
  require(std::isfinite(fault.magnitude), "accepted a magnitude that is not finite");
  require(fault.start_ns >= 0 && fault.duration_ns >= 0, "accepted a negative time");
  // The emulator asks every step whether it acts: must be defined for any time.
  for (const std::int64_t t : {std::int64_t{0}, fault.start_ns, INT64_MAX}) (void)fault.activeAt(t);
}

void modeCommand(const std::uint8_t* data, std::size_t size) {
  msg::ModeCmd command;
  if (!decode<std::remove_cvref_t<decltype(bus::topics::kUnloadingModeCmd)>>(data, size, command)) return;
  const auto mode = unloading_controller::commandedMode(command);
  const auto raw = static_cast<std::uint32_t>(command.mode());
  require(mode.has_value() == (raw <= 2), "mode accepted or refused against the IDL's enum");
  if (mode) require(static_cast<std::uint32_t>(*mode) == raw, "a different mode than commanded");
}

void topicPayload(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return;
  std::size_t index = 0, chosen = data[0];
  std::size_t topics = 0;
  bus::forEachTopic([&](const auto&) { ++topics; });
  chosen %= topics;
  bus::forEachTopic([&](const auto& def) {
    using Def = std::remove_cvref_t<decltype(def)>;
    if (index++ != chosen) return;
    typename Def::Type sample;
    if (!decode<Def>(data + 1, size - 1, sample)) return;
    // What decodes is a sample like any other: its bytes round-trip.
    const auto bytes = bus::serialize<Def>(sample);
    const auto again = bus::serialize<Def>(bus::deserialize<Def>(bytes));
    require(bytes == again, "a decoded sample does not round-trip");
  });
}

}  // namespace flatsat::fuzz
