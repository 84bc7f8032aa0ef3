// SPDX-License-Identifier: Apache-2.0
// A reaction wheel unit's stand-in (components/device_sim/ReactionWheelDevice) against
// the closed form of a rotor under piecewise-constant torque, I_w Ω(t) = I_w Ω0 + ∫τ dt,
// with its delay and limit; and its description (deploy/devices/reaction_wheel.yaml):
// the command frame byte for byte, request/response, and what a description may not say.
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>

#include "components/device_protocol/DeviceProtocol.hpp"
#include "components/device_protocol/FrameCodec.hpp"
#include "components/device_sim/ReactionWheelDevice.hpp"

using namespace flatsat;
using device_sim::ReactionWheelDevice;
using device_sim::ReactionWheelDeviceParams;

namespace {

ReactionWheelDeviceParams wheelUnit(double max_torque_Nm, double delay_s) {
  ReactionWheelDeviceParams p;
  p.wheel_count = 3;
  p.inertia_kg_m2 = {0.12, 0.12, 0.06, 0.0};
  p.max_torque_Nm = max_torque_Nm;
  p.response_delay_s = delay_s;
  return p;
}

/// The wheel topics' fields and units as the IDL gives them (idl/Sensors.idl, Actuation.idl).
std::optional<std::string> wheelUnits(const std::string& topic, const std::string& field) {
  if (topic == "flatsat/wheel_tach" && field.rfind("wheel_speed_rad_s[", 0) == 0) return std::string("rad/s");
  if (topic == "flatsat/wheel_torque_cmd" && field.rfind("torque_Nm[", 0) == 0) return std::string("N m");
  return std::nullopt;
}

/// CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF, no reflection), bit by bit as the
/// catalogue defines it: an independent reckoning of the bytes the codec must write.
std::uint16_t crcCcittFalse(const std::uint8_t* data, std::size_t n) {
  std::uint16_t crc = 0xFFFF;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= static_cast<std::uint16_t>(data[i] << 8);
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 0x8000) ? static_cast<std::uint16_t>((crc << 1) ^ 0x1021) : static_cast<std::uint16_t>(crc << 1);
  }
  return crc;
}

struct WheelDescriptionFile {
  std::filesystem::path path;
  WheelDescriptionFile(const std::string& name, const std::string& text)
      : path(std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "-" + name)) {
    std::ofstream(path) << text;
  }
  ~WheelDescriptionFile() { std::filesystem::remove(path); }
};

}  // namespace

TEST_CASE("a wheel unit acts on a command after its delay, held to its limit, its rotors integrating exactly",
          "[device_sim][unit]") {
  ReactionWheelDevice wheel(wheelUnit(0.05, 0.05));
  wheel.reset({10.0, -5.0, 0.0, 7.0}, 100.0);
  CHECK(wheel.step(100.0)(3) == 0.0);  // no fourth wheel: nothing to report
  // 0.1 N m asked of wheel 1 is held to 0.05; wheel 3 is asked -0.01.
  REQUIRE(wheel.command({0.1, 0.0, -0.01, 1.0}, 100.0));
  CHECK(wheel.step(100.04)(0) == 10.0);  // still within the delay
  CHECK(wheel.appliedTorque().isZero());
  const auto& w = wheel.step(101.0);
  CHECK(w(0) == Approx(10.0 + 0.05 / 0.12 * (101.0 - 100.05)).epsilon(1e-12));
  CHECK(w(1) == -5.0);
  CHECK(w(2) == Approx(-0.01 / 0.06 * (101.0 - 100.05)).epsilon(1e-12));
  CHECK(w(3) == 0.0);
  CHECK(wheel.appliedTorque()(0) == 0.05);
}

TEST_CASE("a wheel unit's commands switch at their own instants, whatever the sampling", "[device_sim][unit]") {
  ReactionWheelDevice wheel(wheelUnit(0.2, 0.05));
  wheel.reset(Eigen::Vector4d::Zero(), 0.0);
  wheel.command({0.02, 0, 0, 0}, 0.0);   // acts at 0.05
  wheel.command({-0.01, 0, 0, 0}, 0.3);  // acts at 0.35
  // One sample at 1 s and the same path cut into 7 ms samples agree with the closed form.
  const double expected = (0.02 * (0.35 - 0.05) - 0.01 * (1.0 - 0.35)) / 0.12;
  ReactionWheelDevice sampled(wheelUnit(0.2, 0.05));
  sampled.reset(Eigen::Vector4d::Zero(), 0.0);
  sampled.command({0.02, 0, 0, 0}, 0.0);
  for (double t = 0.007; t < 0.3; t += 0.007) sampled.step(t);
  sampled.command({-0.01, 0, 0, 0}, 0.3);
  for (double t = 0.3; t < 1.0; t += 0.007) sampled.step(t);
  CHECK(wheel.step(1.0)(0) == Approx(expected).epsilon(1e-12));
  CHECK(sampled.step(1.0)(0) == Approx(expected).epsilon(1e-12));
  // The clock does not run back, and a command with a NaN in it is not taken.
  CHECK(wheel.step(0.5)(0) == Approx(expected).epsilon(1e-12));
  CHECK_FALSE(wheel.command({NAN, 0, 0, 0}, 1.0));
  CHECK(wheel.step(2.0)(0) == Approx(expected - 0.01 / 0.12).epsilon(1e-12));
}

TEST_CASE("a wheel unit's parameters out of range are refused by name", "[device_sim][unit]") {
  auto p = wheelUnit(0.0, -1.0);
  p.inertia_kg_m2(2) = 0.0;
  const auto errors = p.validate();
  REQUIRE(errors.size() == 3);
  CHECK_THAT(errors[0], Catch::Contains("inertia_kg_m2: wheel 3"));
  CHECK_THAT(errors[1], Catch::Contains("max_torque_Nm"));
  CHECK_THAT(errors[2], Catch::Contains("response_delay_s"));
  CHECK_THROWS_AS(ReactionWheelDevice(p), std::invalid_argument);
}

TEST_CASE("the reaction wheel's description: a 23-byte torque command as its layout gives it, answered per command",
          "[device_protocol][unit]") {
  bus::ConfigProblems problems;
  const auto rw = device_protocol::readDeviceProtocol(FLATSAT_SOURCE_DIR "/deploy/devices/reaction_wheel.yaml",
                                                      wheelUnits, problems);
  INFO(problems.joined());
  REQUIRE(problems.empty());
  CHECK(rw.topic == "flatsat/wheel_tach");
  CHECK(rw.command_topic == "flatsat/wheel_torque_cmd");
  CHECK(rw.reply == device_protocol::ReplyMode::kPerCommand);
  REQUIRE(rw.command);
  REQUIRE(rw.command->size() == 23);
  CHECK(rw.frame.size() == 22);
  // torques 0.01, -0.02, 0.125, 0 N m; counter 0x1234
  const auto bytes = device_protocol::encodeFrame(*rw.command, {0x01, 0.01, -0.02, 0.125, 0.0, 0x1234});
  REQUIRE(bytes.size() == 23);
  CHECK(bytes[0] == 0xEB);
  CHECK(bytes[1] == 0x90);
  CHECK(bytes[2] == 0x01);
  const float torques[4] = {0.01f, -0.02f, 0.125f, 0.0f};
  CHECK(std::memcmp(bytes.data() + 3, torques, sizeof torques) == 0);  // little-endian f32 (this host's order)
  CHECK(bytes[19] == 0x34);
  CHECK(bytes[20] == 0x12);
  const std::uint16_t crc = crcCcittFalse(bytes.data() + 2, 19);
  CHECK(bytes[21] == (crc >> 8));
  CHECK(bytes[22] == (crc & 0xFF));
  device_protocol::FrameParser parser(*rw.command);
  std::optional<device_protocol::RawValues> back;
  for (auto b : bytes) back = parser.push(b);
  REQUIRE(back);
  CHECK((*back)[3] == Approx(0.125));
}

TEST_CASE("an actuator's description without its other half is refused, with the reason", "[device_protocol][unit]") {
  const std::string line = "line: {baud: 115200}\n";
  const std::string frame =
      "frame:\n"
      "  sync: \"EB 91\"\n"
      "  fields:\n"
      "    - {name: w1, at: 2, type: f32, scale: 1, to: \"wheel_speed_rad_s[0]\"}\n"
      "  checksum: {kind: sum8, at: 6, covers_from: 2}\n";
  const std::string command =
      "command:\n"
      "  sync: \"EB 90\"\n"
      "  fields:\n"
      "    - {name: t1, at: 2, type: f32, scale: 1, to: \"torque_Nm[0]\"}\n"
      "  checksum: {kind: sum8, at: 6, covers_from: 2}\n";
  const auto problemsOf = [&](const std::string& name, const std::string& text) {
    const WheelDescriptionFile file(name, "name: rw\ntopic: flatsat/wheel_tach\n" + line + text);
    bus::ConfigProblems problems;
    device_protocol::readDeviceProtocol(file.path.string(), wheelUnits, problems);
    return problems.joined();
  };
  CHECK(problemsOf("ok.yaml", "command_topic: flatsat/wheel_torque_cmd\nreply: per_command\n" + frame + command).empty());
  CHECK_THAT(problemsOf("no_topic.yaml", frame + command), Catch::Contains("command: a command frame needs command_topic"));
  CHECK_THAT(problemsOf("no_frame.yaml", "command_topic: flatsat/wheel_torque_cmd\n" + frame),
             Catch::Contains("command_topic: an actuator's command topic needs its command: frame"));
  CHECK_THAT(problemsOf("sensor.yaml", "reply: per_command\n" + frame),
             Catch::Contains("reply: per_command answers command frames"));
  CHECK_THAT(problemsOf("reply.yaml", "reply: sometimes\n" + frame), Catch::Contains("'sometimes' is neither periodic nor per_command"));
  CHECK(problemsOf("rate.yaml", "rate_hz: 50 Hz\n" + frame).empty());
  CHECK_THAT(problemsOf("answers.yaml", "command_topic: flatsat/wheel_torque_cmd\nreply: per_command\nrate_hz: 10 Hz\n" +
                                            frame + command),
             Catch::Contains("rate_hz: a device that answers each command"));
  CHECK_THAT(problemsOf("fast.yaml", "rate_hz: 20000\n" + frame), Catch::Contains("rate_hz: must be in (0, 10 kHz]"));
  CHECK_THAT(problemsOf("slow.yaml", "rate_hz: 2 s\n" + frame), Catch::Contains("rate_hz"));  // a period is no rate
  CHECK_THAT(problemsOf("field.yaml", "command_topic: flatsat/wheel_torque_cmd\n" + frame +
                                          std::string(command).replace(command.find("torque_Nm"), 9, "speed_Nm")),
             Catch::Contains("command.fields[0].to: 'speed_Nm[0]' is not a field of flatsat/wheel_torque_cmd"));
}
