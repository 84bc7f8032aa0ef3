// SPDX-License-Identifier: Apache-2.0
// Serial devices described, not coded (components/device_protocol, deploy/devices):
// the checks against the CRC catalogue, the magnetometer's description against its
// documented frame, exact counts on a corrupted stream, and bad descriptions refused
// at their own line.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "components/device_protocol/DeviceProtocol.hpp"
#include "components/device_protocol/FrameCodec.hpp"

using namespace flatsat::device_protocol;
namespace bus = flatsat::bus;

namespace {

const std::string kMagnetometer = std::string(FLATSAT_SOURCE_DIR) + "/deploy/devices/magnetometer.yaml";

/// The magnetometer topic's fields as the IDL gives them (idl/Sensors.idl).
std::optional<std::string> magnetometerUnits(const std::string& topic, const std::string& field) {
  if (topic == "flatsat/magnetometer" && field.rfind("b_body_T[", 0) == 0) return std::string("T");
  return std::nullopt;
}

DeviceProtocol magnetometer() {
  bus::ConfigProblems problems;
  DeviceProtocol p = readDeviceProtocol(kMagnetometer, magnetometerUnits, problems);
  INFO(problems.joined());
  REQUIRE(problems.empty());
  return p;
}

const std::vector<std::uint8_t> kCheckText = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};

std::uint32_t check(ChecksumSpec::Kind kind, int width, std::uint32_t poly, std::uint32_t init, bool reflect,
                    std::uint32_t xor_out) {
  ChecksumSpec spec{kind, width, poly, init, reflect, reflect, xor_out};
  REQUIRE(spec.validate().empty());
  return computeChecksum(spec, kCheckText);
}

/// A description laid in a file of this process's own; removed with the object.
struct DescriptionFile {
  std::filesystem::path path;
  explicit DescriptionFile(const std::string& name, const std::string& text)
      : path(std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "-" + name)) {
    std::ofstream(path) << text;
  }
  ~DescriptionFile() { std::filesystem::remove(path); }
};

}  // namespace

TEST_CASE("device checks reproduce the CRC catalogue's check values", "[device_protocol][unit]") {
  // Check values for "123456789" (Williams 1993; the CRC RevEng catalogue).
  using K = ChecksumSpec::Kind;
  CHECK(check(K::kCrc, 16, 0x1021, 0xFFFF, false, 0) == 0x29B1);            // CRC-16/CCITT-FALSE (IBM-3740)
  CHECK(check(K::kCrc, 16, 0x1021, 0x0000, false, 0) == 0x31C3);            // CRC-16/XMODEM
  CHECK(check(K::kCrc, 16, 0x8005, 0x0000, true, 0) == 0xBB3D);             // CRC-16/ARC
  CHECK(check(K::kCrc, 16, 0x8005, 0xFFFF, true, 0) == 0x4B37);             // CRC-16/MODBUS
  CHECK(check(K::kCrc, 32, 0x04C11DB7, 0xFFFFFFFF, true, 0xFFFFFFFF) == 0xCBF43926);  // CRC-32 (ISO-HDLC)
  CHECK(check(K::kCrc, 32, 0x04C11DB7, 0xFFFFFFFF, false, 0) == 0x0376E6E7);          // CRC-32/MPEG-2
  CHECK(check(K::kCrc, 8, 0x07, 0x00, false, 0) == 0xF4);                   // CRC-8 (SMBus)
  CHECK(check(K::kSum8, 8, 1, 0, false, 0) == 0xDD);  // 0x31 + … + 0x39 = 0x1DD
  CHECK(check(K::kSum8, 8, 1, 0, false, 0xFF) == 0x22);  // "~sum": the complement
  CHECK(check(K::kXor8, 8, 1, 0, false, 0) == 0x31);
  CHECK_FALSE(ChecksumSpec{K::kCrc, 12, 0x80F, 0, false, false, 0}.validate().empty());
  CHECK_FALSE(ChecksumSpec{K::kCrc, 16, 0x1020, 0, false, false, 0}.validate().empty());  // even generator
}

TEST_CASE("the magnetometer's description gives its documented 22-byte frame", "[device_protocol][unit]") {
  const DeviceProtocol p = magnetometer();
  CHECK(p.name == "magnetometer");
  CHECK(p.topic == "flatsat/magnetometer");
  CHECK(p.sensor_axes == "magnetometer");
  CHECK(p.line.baud == 115200);
  REQUIRE(p.frame.size() == 22);
  CHECK(p.frame.fields[3].scale == Approx(1e-9).epsilon(1e-15));  // 1 nT per count, in the topic's T
  // Sequence 0x01020304, field (-21000, 1500, 43000) nT, laid out by hand per the header
  // of magnetometer.yaml: AA 55, type 01, length 10, then little-endian words.
  const std::vector<std::uint8_t> head = {0xAA, 0x55, 0x01, 0x10, 0x04, 0x03, 0x02, 0x01,
                                          0xF8, 0xAD, 0xFF, 0xFF,  // −21000
                                          0xDC, 0x05, 0x00, 0x00,  // 1500
                                          0xF8, 0xA7, 0x00, 0x00};  // 43000
  const std::vector<std::uint8_t> frame = encodeFrame(p.frame, {0, 0, 0x01020304, -21000, 1500, 43000});
  REQUIRE(frame.size() == 22);
  CHECK(std::vector<std::uint8_t>(frame.begin(), frame.begin() + 20) == head);
  ChecksumSpec ccitt_false;  // the defaults are CRC-16/CCITT-FALSE, checked above
  const std::uint32_t crc = computeChecksum(ccitt_false, std::span(head).subspan(2));
  CHECK(frame[20] == (crc & 0xFF));
  CHECK(frame[21] == (crc >> 8));

  FrameParser parser(p.frame);
  std::optional<RawValues> out;
  for (const std::uint8_t byte : frame) {
    REQUIRE_FALSE(out);
    out = parser.push(byte);
  }
  REQUIRE(out);
  CHECK(*out == RawValues{1, 16, 0x01020304, -21000, 1500, 43000});
  // Counts held to their type: a field beyond ±2^31 nT saturates rather than wraps.
  const auto held = encodeFrame(p.frame, {0, 0, 1, 3e9, -3e9, 0.4});
  CHECK(decodeField(p.frame.fields[3], held.data()) == 2147483647.0);
  CHECK(decodeField(p.frame.fields[4], held.data()) == -2147483648.0);
  CHECK(decodeField(p.frame.fields[5], held.data()) == 0.0);
}

TEST_CASE("10^4 corrupted frames among good ones through the described parser: exact counts",
          "[device_protocol][unit]") {
  const FrameSpec spec = magnetometer().frame;
  std::mt19937 rng(2026);
  std::uniform_int_distribution<int> field(-65000, 65000), kind(0, 4), noise_byte(0, 255), length(1, 40);
  std::uint32_t sequence = 0;
  // A frame whose bytes after the sync hold no 0xAA: a corrupted copy then cannot hide a
  // second sync pattern, so the expected counts are exact.
  const auto cleanFrame = [&](RawValues& raw) {
    for (;;) {
      raw = {0, 0, static_cast<double>(sequence++), double(field(rng)), double(field(rng)), double(field(rng))};
      const auto frame = encodeFrame(spec, raw);
      if (std::find(frame.begin() + 2, frame.end(), 0xAA) == frame.end()) return frame;
    }
  };
  std::vector<std::uint8_t> stream;
  std::vector<RawValues> good;
  std::uint64_t bad_checksum = 0, bad_header = 0, noise = 0;
  for (int i = 0; i < 10000; ++i) {
    RawValues raw;
    const auto frame = cleanFrame(raw);
    stream.insert(stream.end(), frame.begin(), frame.end());
    good.push_back({1, 16, raw[2], raw[3], raw[4], raw[5]});
    auto bad = cleanFrame(raw);
    switch (kind(rng)) {
      case 0:  // a flipped payload bit
        bad[9] ^= 0x10;
        if (bad[9] == 0xAA) bad[9] ^= 0x01;
        ++bad_checksum;
        break;
      case 1:  // wrong length byte
        bad[3] = 15;
        ++bad_header;
        break;
      case 2:  // unknown type
        bad[2] = 0x02;
        ++bad_header;
        break;
      case 3:  // check bytes lost on the line
        bad[21] = bad[20] = 0;
        ++bad_checksum;
        break;
      default: {  // line noise without a sync byte
        const int n = length(rng);
        for (int b = 0; b < n; ++b) {
          const int v = noise_byte(rng);
          stream.push_back(static_cast<std::uint8_t>(v == 0xAA ? 0 : v));
        }
        noise += static_cast<std::uint64_t>(n);
        continue;
      }
    }
    // A broken check could, by chance, be right: then the frame is good.
    if (bad[2] == 0x01 && bad[3] == 16 && computeChecksum(spec.checksum, std::span(bad).subspan(2, 18)) ==
                                                  static_cast<std::uint32_t>(bad[20] | bad[21] << 8)) {
      --bad_checksum;
      good.push_back({1, 16, raw[2], raw[3], raw[4], raw[5]});
    }
    stream.insert(stream.end(), bad.begin(), bad.end());
  }
  FrameParser parser(spec);
  std::vector<RawValues> delivered;
  for (const std::uint8_t byte : stream) {
    if (auto values = parser.push(byte)) delivered.push_back(*values);
  }
  REQUIRE(delivered.size() == good.size());
  CHECK(delivered == good);
  CHECK(parser.counts().frames == good.size());
  CHECK(parser.counts().bad_checksum == bad_checksum);
  CHECK(parser.counts().bad_header == bad_header);
  // Each rejected candidate leaves its 21 remaining bytes, none a sync, as skipped bytes;
  // noise is skipped byte for byte.
  CHECK(parser.counts().skipped_bytes == noise + (bad_checksum + bad_header) * 21);
}

TEST_CASE("big-endian floats and a one-byte sum: a frame whose check passes but carries NaN is refused",
          "[device_protocol][unit]") {
  FrameSpec spec;
  spec.sync = {0xFE, 0x81};
  spec.fields = {{"w", 2, FieldType::kF32, false, {}, false, 1.0, "w"}, {"seq", 6, FieldType::kU8, false, {}, true, 1.0, ""}};
  spec.checksum.kind = ChecksumSpec::Kind::kSum8;
  spec.checksum.width_bits = 8;
  spec.checksum.init = 0;
  spec.checksum_at = spec.covers_to = 7;
  spec.covers_from = 2;
  REQUIRE(spec.validate().empty());
  const auto frame = encodeFrame(spec, {0.25, 9});
  CHECK(std::vector<std::uint8_t>(frame.begin() + 2, frame.begin() + 6) == std::vector<std::uint8_t>{0x3E, 0x80, 0x00, 0x00});
  CHECK(frame[6] == 9);
  CHECK(frame[7] == ((0x3E + 0x80 + 9) & 0xFF));
  FrameParser parser(spec);
  const auto nan = encodeFrame(spec, {std::numeric_limits<double>::quiet_NaN(), 10});
  for (const std::uint8_t byte : nan) CHECK_FALSE(parser.push(byte));
  CHECK(parser.counts().bad_value == 1);
  std::optional<RawValues> out;
  for (const std::uint8_t byte : frame) out = parser.push(byte);
  REQUIRE(out);
  CHECK((*out)[0] == 0.25);
}

TEST_CASE("a bad device description is refused at its own line, with the reason", "[device_protocol][unit]") {
  const std::string head =
      "name: broken\n"
      "topic: flatsat/magnetometer\n"
      "line: {baud: 115200}\n"
      "frame:\n"
      "  sync: \"AA 55\"\n"
      "  fields:\n";
  const auto problemsOf = [&](const std::string& name, const std::string& fields, const std::string& checksum) {
    const DescriptionFile file(name, head + fields + "  checksum: " + checksum + "\n");
    bus::ConfigProblems problems;
    readDeviceProtocol(file.path.string(), magnetometerUnits, problems);
    return problems.joined();
  };
  const std::string crc = "{poly: 0x1021, init: 0xFFFF, at: 8, covers_from: 2}";
  const std::string good =  // lines 7 to 9
      "    - {name: type, at: 2, type: u8, const: 1}\n"
      "    - {name: bx, at: 3, type: i32, scale: 1 nT, to: \"b_body_T[0]\"}\n"
      "    - {name: pad, at: 7, type: u8}\n";
  const auto changed = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    return text.replace(text.find(from), from.size(), to);
  };
  CHECK(problemsOf("ok.yaml", good, crc).empty());
  const std::string overlap = problemsOf("overlap.yaml", changed("{name: pad, at: 7, type: u8}", "{name: by, at: 5, type: u16}"), crc);
  CHECK_THAT(overlap, Catch::Contains("overlap.yaml:9:") && Catch::Contains("field 'by' (bytes 5..6) overlaps field 'bx'"));
  const std::string unknown_type = problemsOf("type.yaml", changed("type: i32", "type: int24"), crc);
  CHECK_THAT(unknown_type, Catch::Contains("type.yaml:8:") && Catch::Contains("frame.fields[1].type: 'int24' is not u8"));
  const std::string uncovered = problemsOf("covers.yaml", good, "{poly: 0x1021, init: 0xFFFF, at: 8, covers_from: 3}");
  CHECK_THAT(uncovered, Catch::Contains("covers.yaml:10:") && Catch::Contains("it must cover every byte from 2"));
  const std::string unit = problemsOf("unit.yaml", changed("scale: 1 nT", "scale: 0.01 deg"), crc);
  CHECK_THAT(unit, Catch::Contains("unit.yaml:8:") && Catch::Contains("frame.fields[1].scale"));
  const std::string gap = problemsOf("gap.yaml", changed("    - {name: pad, at: 7, type: u8}\n", ""), crc);
  CHECK_THAT(gap, Catch::Contains("byte 7 belongs to no field"));
  const std::string wrong_check =
      problemsOf("check.yaml", good, "{poly: 0x1021, init: 0x0000, at: 8, covers_from: 2, check: 0x29B1}");
  CHECK_THAT(wrong_check, Catch::Contains("frame.checksum.check: the parameters give another check value"));
  std::string misnamed = changed("const: 1}", "const: 300}");
  misnamed.replace(misnamed.find("b_body_T"), 8, "b_body_X");
  const std::string elsewhere = problemsOf("field.yaml", misnamed, crc);
  CHECK_THAT(elsewhere, Catch::Contains("frame.fields[0].const: does not fit") &&
                            Catch::Contains("'b_body_X[0]' is not a field of flatsat/magnetometer"));
  CHECK_THAT(problemsOf("far.yaml", changed("at: 7, type: u8", "at: 18446744073709551615, type: u8"), crc),
             Catch::Contains("frame.fields[2].at: beyond the longest frame, 1024 bytes"));
  CHECK_THAT(problemsOf("signed.yaml", changed("{name: pad, at: 7, type: u8}", "{name: pad, at: 7, type: i8, sequence: true}"), crc),
             Catch::Contains("a sample counter must be an unsigned integer"));
  CHECK_THAT(problemsOf("sum.yaml", good, "{kind: sum8, poly: 0x07, at: 8, covers_from: 2}"),
             Catch::Contains("frame.checksum.poly: a CRC's parameter: sum8 has none"));
  const DescriptionFile seven("seven.yaml", std::string(head).replace(head.find("{baud: 115200}"), 14, "{baud: 115200, data_bits: 7}") +
                                                good + "  checksum: " + crc + "\n");
  bus::ConfigProblems seven_bits;
  readDeviceProtocol(seven.path.string(), magnetometerUnits, seven_bits);
  CHECK_THAT(seven_bits.joined(), Catch::Contains("line.data_bits: 7 must be 8 for binary frames"));
  FrameSpec inexact;
  inexact.sync = {0xAA};
  inexact.fields = {{"k", 1, FieldType::kF32, true, 0.1, false, 1.0, ""}};
  inexact.checksum_at = inexact.covers_to = 5;
  inexact.covers_from = 1;
  REQUIRE(inexact.validate().size() == 1);
  CHECK(inexact.validate()[0].reason == "does not fit the field's type");  // 0.1 is no float
  CHECK_THROWS_AS(FrameParser(inexact), std::invalid_argument);
  CHECK_THROWS_AS(encodeFrame(magnetometer().frame, {1, 2}), std::invalid_argument);
  bus::ConfigProblems missing;
  readDeviceProtocol("/nonexistent/device.yaml", magnetometerUnits, missing);
  CHECK_THAT(missing.joined(), Catch::Contains("/nonexistent/device.yaml: cannot read"));
}
