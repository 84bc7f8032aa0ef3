// SPDX-License-Identifier: Apache-2.0
// The generic device bridge on the shipped descriptions: a frame's counts to its topic's
// fields in their units, the device's axes to body axes, full scale, sequence gaps (a wrap
// is none), `valid` for a good frame, and the device end's inverse to within half a count.
#include <cmath>

#include <catch2/catch.hpp>

#include "components/device_bridge/DeviceBridge.hpp"
#include "components/device_protocol/DeviceProtocol.hpp"

using namespace flatsat;
using device_bridge::DeviceBridge;
using device_bridge::DeviceBridgeParams;
using device_bridge::FrameMapping;

namespace {

// The leaves of the topics' IDL types (idl/Sensors.idl), in order, with their units.
const std::vector<std::pair<std::string, std::string>> kMagnetometerLeaves = {
    {"header.step", "-"}, {"header.sim_time_ns", "ns"}, {"header.sample_time_ns", "ns"}, {"header.source", "-"},
    {"b_body_T[0]", "T"}, {"b_body_T[1]", "T"},           {"b_body_T[2]", "T"},           {"saturated", "-"},
    {"valid", "-"}};
const std::vector<std::pair<std::string, std::string>> kGyroLeaves = {
    {"header.step", "-"},       {"header.sim_time_ns", "ns"}, {"header.sample_time_ns", "ns"},
    {"header.source", "-"},     {"w_body_rad_s[0]", "rad/s"}, {"w_body_rad_s[1]", "rad/s"},
    {"w_body_rad_s[2]", "rad/s"}, {"valid", "-"}};
const std::vector<std::pair<std::string, std::string>> kSunSensorLeaves = [] {
  std::vector<std::pair<std::string, std::string>> leaves = {
      {"header.step", "-"},      {"header.sim_time_ns", "ns"}, {"header.sample_time_ns", "ns"}, {"header.source", "-"},
      {"sun_body_unit[0]", "-"}, {"sun_body_unit[1]", "-"},    {"sun_body_unit[2]", "-"},       {"valid", "-"},
      {"cell_count", "-"}};
  for (int i = 0; i < 12; ++i) leaves.emplace_back("cell_output[" + std::to_string(i) + "]", "-");
  return leaves;
}();

std::vector<std::string> names(const std::vector<std::pair<std::string, std::string>>& leaves) {
  std::vector<std::string> out;
  for (const auto& leaf : leaves) out.push_back(leaf.first);
  return out;
}

struct Shipped {
  device_protocol::DeviceProtocol protocol;
  FrameMapping mapping;
};

Shipped shipped(const std::string& device, const std::vector<std::pair<std::string, std::string>>& leaves) {
  bus::ConfigProblems problems;
  const auto unit_of = [&](const std::string&, const std::string& field) -> std::optional<std::string> {
    for (const auto& [name, unit] : leaves) {
      if (name == field) return unit;
    }
    return std::nullopt;
  };
  const auto protocol =
      device_protocol::readDeviceProtocol(FLATSAT_SOURCE_DIR "/deploy/devices/" + device + ".yaml", unit_of, problems);
  INFO(problems.joined());
  REQUIRE(problems.empty());
  std::string why;
  const auto mapping = FrameMapping::of(protocol.frame, names(leaves), why);
  INFO(why);
  REQUIRE(mapping);
  return {protocol, *mapping};
}

/// The value a sample gives leaf `leaf`; NAN when it gives none.
double valueOf(const device_bridge::BridgeSample& sample, std::size_t leaf) {
  for (const auto& [index, value] : sample.leaves) {
    if (index == leaf) return value;
  }
  return NAN;
}

Eigen::Vector3d vectorAt(const device_bridge::BridgeSample& sample, std::size_t first_leaf) {
  return {valueOf(sample, first_leaf), valueOf(sample, first_leaf + 1), valueOf(sample, first_leaf + 2)};
}

}  // namespace

TEST_CASE("the magnetometer's frame becomes the body field, valid, saturated at full scale", "[device_bridge][unit]") {
  const Shipped s = shipped("magnetometer", kMagnetometerLeaves);
  CHECK(s.mapping.body_vectors.size() == 1);
  CHECK(s.mapping.valid_leaf == 8u);
  CHECK(s.mapping.saturated_leaf == 7u);
  DeviceBridgeParams params;
  // Mounted 90 deg about z: sensor x is body y, sensor y is body −x.
  params.q_body_sensor = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  DeviceBridge bridge(params, s.mapping);
  // Values in the frame's field order: type, length, sequence, bx, by, bz.
  const auto out = bridge.step({1, 16, 4294967295.0, 20000, -5000, 30000});
  CHECK(vectorAt(out, 4).isApprox(Eigen::Vector3d(5000e-9, 20000e-9, 30000e-9), 1e-12));
  CHECK(valueOf(out, 8) == 1.0);
  CHECK(valueOf(out, 7) == 0.0);
  CHECK(out.missed_samples == 0);
  // The counter wraps to 0: no gap. Then 3 is two frames lost.
  CHECK(bridge.step({1, 16, 0, 0, 0, 0}).missed_samples == 0);
  CHECK(bridge.step({1, 16, 3, 0, 0, 0}).missed_samples == 2);
  const auto at_full_scale = bridge.step({1, 16, 4, 100000, 0, 0});  // 100 µT on one axis
  CHECK(at_full_scale.saturated);
  CHECK(valueOf(at_full_scale, 7) == 1.0);
  bridge.reset();
  CHECK(bridge.step({1, 16, 9, 0, 0, 0}).missed_samples == 0);  // nothing to compare with after a reset
}

TEST_CASE("a frame that carries part of a body vector, a field twice or a field the topic lacks is refused",
          "[device_bridge][unit]") {
  const Shipped s = shipped("magnetometer", kMagnetometerLeaves);
  std::string why;
  auto no_z = s.protocol.frame;
  no_z.fields[5].maps_to.clear();
  CHECK_FALSE(FrameMapping::of(no_z, names(kMagnetometerLeaves), why));
  CHECK(why == "'b_body_T' is a body-axes vector: the frame must carry its three components (x, y, z)");
  auto twice = s.protocol.frame;
  twice.fields[5].maps_to = "b_body_T[1]";
  CHECK_FALSE(FrameMapping::of(twice, names(kMagnetometerLeaves), why));
  CHECK(why == "two fields go to 'b_body_T[1]'");
  CHECK_FALSE(FrameMapping::of(s.protocol.frame, names(kGyroLeaves), why));
  CHECK(why == "field 'bx' goes to 'b_body_T[0]', which the topic does not have");
}

TEST_CASE("the device end writes the body field as the frame's counts, clipped at full scale", "[device_bridge][unit]") {
  const Shipped s = shipped("magnetometer", kMagnetometerLeaves);
  DeviceBridgeParams mounting;
  mounting.q_body_sensor = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Vector3d b_B(21.34567e-6, -8.76543e-6, 40.1e-6);
  std::vector<double> topic(kMagnetometerLeaves.size(), 0.0);
  for (int k = 0; k < 3; ++k) topic[4 + static_cast<std::size_t>(k)] = b_B[k];
  const auto raw = device_bridge::deviceFrame(topic, mounting, s.protocol.frame, s.mapping, 77);
  CHECK(raw[2] == 77.0);
  DeviceBridge bridge(mounting, s.mapping);
  // Whole nanotesla per sensor axis: back in body axes within √3/2 nT.
  CHECK((vectorAt(bridge.step(raw), 4) - b_B).norm() <= std::sqrt(3.0) * 0.5e-9);
  topic[6] = 1e-3;
  const auto clipped = device_bridge::deviceFrame(topic, DeviceBridgeParams{}, s.protocol.frame, s.mapping, 0);
  // 100 µT full scale, in whole nT counts on the wire.
  const auto bytes = device_protocol::encodeFrame(s.protocol.frame, clipped);
  CHECK(device_protocol::decodeField(s.protocol.frame.fields[5], bytes.data()) == 100000.0);
}

TEST_CASE("the gyro's big-endian datagram: its bytes as a data sheet gives them, and the rate in rad/s",
          "[device_bridge][unit]") {
  const Shipped s = shipped("gyro", kGyroLeaves);
  CHECK(s.protocol.frame.size() == 20);
  CHECK(s.mapping.sequence_modulus == 256);
  CHECK(s.mapping.valid_leaf == 7u);  // no field carries it: a good frame is a measurement
  CHECK_FALSE(s.mapping.saturated_leaf);
  // 1, −2 and 0.5 deg/s in 1e-6 deg/s counts, high byte first.
  std::vector<double> topic(kGyroLeaves.size(), 0.0);
  const double deg = M_PI / 180.0;
  topic[4] = 1.0 * deg;
  topic[5] = -2.0 * deg;
  topic[6] = 0.5 * deg;
  const auto raw = device_bridge::deviceFrame(topic, DeviceBridgeParams{}, s.protocol.frame, s.mapping, 258);
  const auto bytes = device_protocol::encodeFrame(s.protocol.frame, raw);
  const std::vector<std::uint8_t> expected_head = {0xA5, 0x93, 0x00, 0x0F, 0x42, 0x40, 0xFF, 0xE1, 0x7B,
                                                   0x80, 0x00, 0x07, 0xA1, 0x20, 0x00, 0x02};
  CHECK(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 16) == expected_head);  // counter 258 mod 256
  // CRC-32/MPEG-2 over bytes 1..15, reckoned bit by bit as the catalogue defines it
  // (poly 0x04C11DB7, init 0xFFFFFFFF, no reflection, no final xor), high byte first.
  std::uint32_t crc = 0xFFFFFFFF;
  for (std::size_t i = 1; i < 16; ++i) {
    crc ^= static_cast<std::uint32_t>(bytes[i]) << 24;
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 0x80000000u) ? (crc << 1) ^ 0x04C11DB7u : crc << 1;
  }
  CHECK(std::vector<std::uint8_t>(bytes.begin() + 16, bytes.end()) ==
        std::vector<std::uint8_t>{static_cast<std::uint8_t>(crc >> 24), static_cast<std::uint8_t>(crc >> 16),
                                  static_cast<std::uint8_t>(crc >> 8), static_cast<std::uint8_t>(crc)});
  device_protocol::FrameParser parser(s.protocol.frame);
  std::optional<device_protocol::RawValues> parsed;
  for (auto b : bytes) parsed = parser.push(b);
  REQUIRE(parsed);
  DeviceBridge bridge(DeviceBridgeParams{}, s.mapping);
  CHECK(vectorAt(bridge.step(*parsed), 4).isApprox(Eigen::Vector3d(1.0, -2.0, 0.5) * deg, 1e-12));
}

TEST_CASE("the Sun sensor's frame carries its own valid flag, and zeros when the Sun is not measured",
          "[device_bridge][unit]") {
  const Shipped s = shipped("sun_sensor", kSunSensorLeaves);
  CHECK_FALSE(s.mapping.valid_leaf);  // the frame carries it
  CHECK(s.protocol.line.parity == "even");
  std::vector<double> topic(kSunSensorLeaves.size(), 0.0);
  const Eigen::Vector3d sun = Eigen::Vector3d(0.8, -0.36, 0.48).normalized();
  for (int k = 0; k < 3; ++k) topic[4 + static_cast<std::size_t>(k)] = sun[k];
  topic[7] = 1.0;
  DeviceBridge bridge(DeviceBridgeParams{}, s.mapping);
  const auto seen = bridge.step(device_bridge::deviceFrame(topic, DeviceBridgeParams{}, s.protocol.frame, s.mapping, 1));
  CHECK((vectorAt(seen, 4) - sun).cwiseAbs().maxCoeff() <= 0.5 / 32000 + 1e-15);  // half a count
  CHECK(valueOf(seen, 7) == 1.0);
  std::fill(topic.begin(), topic.end(), 0.0);
  const auto unseen = bridge.step(device_bridge::deviceFrame(topic, DeviceBridgeParams{}, s.protocol.frame, s.mapping, 2));
  CHECK(valueOf(unseen, 7) == 0.0);
  CHECK(vectorAt(unseen, 4).isZero());
  CHECK(unseen.missed_samples == 0);
}

TEST_CASE("a one-byte counter wraps without a gap, and the device end writes it modulo 256", "[device_bridge][unit]") {
  using device_protocol::FieldSpec;
  using device_protocol::FieldType;
  device_protocol::FrameSpec frame;
  frame.name = "compact";
  frame.sync = {0x5A};
  frame.fields = {FieldSpec{"seq", 1, FieldType::kU8, true, {}, true, 1.0, "", {}}};
  for (std::size_t i = 0; i < 3; ++i) {
    frame.fields.push_back({"b" + std::to_string(i), 2 + 2 * i, FieldType::kI16, true, {}, false, 4e-9,
                            "b_body_T[" + std::to_string(i) + "]", {}});
  }
  frame.checksum.kind = device_protocol::ChecksumSpec::Kind::kSum8;
  frame.checksum.width_bits = 8;
  frame.checksum.init = 0;
  frame.checksum_at = frame.covers_to = 8;
  frame.covers_from = 1;
  REQUIRE(frame.validate().empty());
  std::string why;
  const auto mapping = FrameMapping::of(frame, names(kMagnetometerLeaves), why);
  REQUIRE(mapping);
  CHECK(mapping->sequence_modulus == 256);
  DeviceBridge bridge(DeviceBridgeParams{}, *mapping);
  CHECK(bridge.step({254, 0, 0, 0}).missed_samples == 0);
  CHECK(bridge.step({255, 0, 0, 0}).missed_samples == 0);
  CHECK(bridge.step({0, 0, 0, 0}).missed_samples == 0);    // the wrap
  CHECK(bridge.step({3, 0, 0, 0}).missed_samples == 2);    // 1 and 2 lost
  CHECK(bridge.step({1, 0, 0, 0}).missed_samples == 253);  // an old frame again: read as a long gap
  // The device end: 300 as the counter's 44; 10 µT in 4 nT counts, rounded by the encoder.
  std::vector<double> topic(kMagnetometerLeaves.size(), 0.0);
  topic[4] = 10e-6;
  topic[6] = -6e-9;
  const auto raw = device_bridge::deviceFrame(topic, DeviceBridgeParams{}, frame, *mapping, 300);
  CHECK(raw[0] == 44.0);
  const auto bytes = device_protocol::encodeFrame(frame, raw);
  CHECK(device_protocol::decodeField(frame.fields[1], bytes.data()) == 2500.0);
  CHECK(device_protocol::decodeField(frame.fields[3], bytes.data()) == -2.0);  // −1.5 counts, to the nearest even
}

TEST_CASE("a value that a double cannot hold once scaled makes the sample unusable, never infinite on the bus",
          "[device_bridge][unit]") {
  device_protocol::FrameSpec frame;
  frame.name = "huge";
  frame.sync = {0xAA};
  frame.fields = {{"c", 1, device_protocol::FieldType::kF64, true, std::nullopt, false, 1e10, "cell_output[0]"}};
  frame.checksum = {device_protocol::ChecksumSpec::Kind::kSum8, 8, 0, 0, false, false, 0};
  frame.checksum_at = frame.covers_to = 9;
  frame.covers_from = 1;
  REQUIRE(frame.validate().empty());
  std::string why;
  const auto mapping = FrameMapping::of(frame, names(kSunSensorLeaves), why);
  REQUIRE(mapping);
  DeviceBridge bridge(DeviceBridgeParams{}, *mapping);
  CHECK(bridge.step({1e300}).finite == false);  // 1e310 is past DBL_MAX
  CHECK(bridge.step({1e290}).finite);
}
