// SPDX-License-Identifier: Apache-2.0
// The magnetometer bridge's conversion on its shipped description: counts in sensor axes
// to tesla in body axes, full scale, sequence gaps (a wrap is none), and the device end's
// inverse to within half a count.
#include <cmath>

#include <catch2/catch.hpp>

#include "components/device_protocol/DeviceProtocol.hpp"
#include "components/magnetometer_bridge/MagnetometerBridge.hpp"

using namespace flatsat;
using magnetometer_bridge::MagnetometerBridge;
using magnetometer_bridge::MagnetometerBridgeParams;
using magnetometer_bridge::MagnetometerFields;

namespace {

struct Shipped {
  device_protocol::FrameSpec frame;
  MagnetometerFields fields;
};

Shipped shipped() {
  bus::ConfigProblems problems;
  const auto tesla = [](const std::string&, const std::string&) { return std::optional<std::string>("T"); };
  const auto protocol =
      device_protocol::readDeviceProtocol(FLATSAT_SOURCE_DIR "/deploy/devices/magnetometer.yaml", tesla, problems);
  REQUIRE(problems.empty());
  std::string why;
  const auto fields = MagnetometerFields::of(protocol.frame, why);
  REQUIRE(fields);
  return {protocol.frame, *fields};
}

}  // namespace

TEST_CASE("the magnetometer bridge turns a frame's counts into the body field", "[magnetometer_bridge][unit]") {
  const Shipped s = shipped();
  MagnetometerBridgeParams params;
  // Mounted 90 deg about z: sensor x is body y, sensor y is body −x.
  params.q_body_sensor = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  params.range_T = 60e-6;
  MagnetometerBridge bridge(params, s.fields);
  // Values in the frame's field order: type, length, sequence, bx, by, bz.
  const auto out = bridge.step({1, 16, 4294967295.0, 20000, -5000, 30000});
  CHECK(out.b_B_T.isApprox(Eigen::Vector3d(5000e-9, 20000e-9, 30000e-9), 1e-12));
  CHECK_FALSE(out.saturated);
  CHECK(out.missed_samples == 0);
  // The counter wraps to 0: no gap. Then 3 is two frames lost.
  CHECK(bridge.step({1, 16, 0, 0, 0, 0}).missed_samples == 0);
  CHECK(bridge.step({1, 16, 3, 0, 0, 0}).missed_samples == 2);
  CHECK(bridge.step({1, 16, 4, 60000, 0, 0}).saturated);  // at full scale on one axis
  bridge.reset();
  CHECK(bridge.step({1, 16, 9, 0, 0, 0}).missed_samples == 0);  // nothing to compare with after a reset

  std::string why;
  device_protocol::FrameSpec no_z = s.frame;
  no_z.fields[5].maps_to.clear();
  CHECK_FALSE(MagnetometerFields::of(no_z, why));
  CHECK(why == "no field of frame 'field_sample' carries b_body_T[2]");
}

TEST_CASE("the device end writes the body field as the frame's counts, clipped at full scale",
          "[magnetometer_bridge][unit]") {
  const Shipped s = shipped();
  MagnetometerBridgeParams mounting;
  mounting.q_body_sensor = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Vector3d b_B(21.34567e-6, -8.76543e-6, 40.1e-6);
  const auto raw = magnetometer_bridge::deviceFrame(b_B, mounting, s.frame, s.fields, 77);
  CHECK(raw[2] == 77.0);
  MagnetometerBridge bridge(mounting, s.fields);
  // Whole nanotesla per sensor axis: back in body axes within √3/2 nT.
  CHECK((bridge.step(raw).b_B_T - b_B).norm() <= std::sqrt(3.0) * 0.5e-9);
  const auto clipped = magnetometer_bridge::deviceFrame(Eigen::Vector3d(0.0, 0.0, 1e-3), MagnetometerBridgeParams{},
                                                        s.frame, s.fields, 0);
  CHECK(clipped[5] == 100000.0);  // 100 uT full scale, in nT counts
}

TEST_CASE("a one-byte counter wraps without a gap, and the device end writes it modulo 256",
          "[magnetometer_bridge][unit]") {
  using device_protocol::FieldSpec;
  using device_protocol::FieldType;
  device_protocol::FrameSpec frame;
  frame.name = "compact";
  frame.sync = {0x5A};
  frame.fields = {FieldSpec{"seq", 1, FieldType::kU8, true, {}, true, 1.0, ""}};
  for (std::size_t i = 0; i < 3; ++i) {
    frame.fields.push_back({"b" + std::to_string(i), 2 + 2 * i, FieldType::kI16, true, {}, false, 4e-9,
                            "b_body_T[" + std::to_string(i) + "]"});
  }
  frame.checksum.kind = device_protocol::ChecksumSpec::Kind::kSum8;
  frame.checksum.width_bits = 8;
  frame.checksum.init = 0;
  frame.checksum_at = frame.covers_to = 8;
  frame.covers_from = 1;
  REQUIRE(frame.validate().empty());
  std::string why;
  const auto fields = MagnetometerFields::of(frame, why);
  REQUIRE(fields);
  CHECK(fields->sequence_modulus == 256);
  MagnetometerBridge bridge(MagnetometerBridgeParams{}, *fields);
  CHECK(bridge.step({254, 0, 0, 0}).missed_samples == 0);
  CHECK(bridge.step({255, 0, 0, 0}).missed_samples == 0);
  CHECK(bridge.step({0, 0, 0, 0}).missed_samples == 0);    // the wrap
  CHECK(bridge.step({3, 0, 0, 0}).missed_samples == 2);    // 1 and 2 lost
  CHECK(bridge.step({1, 0, 0, 0}).missed_samples == 253);  // an old frame again: read as a long gap
  // The device end: 300 as the counter's 44; 10 µT in 4 nT counts, rounded by the encoder.
  const auto raw = magnetometer_bridge::deviceFrame(Eigen::Vector3d(10e-6, 0.0, -6e-9), MagnetometerBridgeParams{}, frame,
                                                    *fields, 300);
  CHECK(raw[0] == 44.0);
  const auto bytes = device_protocol::encodeFrame(frame, raw);
  CHECK(device_protocol::decodeField(frame.fields[1], bytes.data()) == 2500.0);
  CHECK(device_protocol::decodeField(frame.fields[3], bytes.data()) == -2.0);  // −1.5 counts, to the nearest even
}
