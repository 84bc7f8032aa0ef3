// SPDX-License-Identifier: Apache-2.0
// The magnetometer serial protocol: frames round-trip, and a stream of good
// frames mixed with 10^4 corrupted ones (bad CRC, bad header, truncated,
// line noise) delivers exactly the good frames, with counts that match.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "components/magnetometer_bridge/MagnetometerFrame.hpp"

using namespace flatsat::magnetometer_bridge;

namespace {

/// A frame whose bytes after the sync hold no 0xAA: a corrupted copy then
/// cannot hide a second sync pattern, so the expected counts are exact.
std::array<std::uint8_t, kFrameSize> cleanFrame(std::mt19937& rng, std::uint32_t& sequence,
                                                FieldSample& sample) {
  std::uniform_int_distribution<std::int32_t> field(-65000, 65000);
  for (;;) {
    sample = {sequence++, {field(rng), field(rng), field(rng)}};
    const auto frame = encodeFrame(sample);
    if (std::find(frame.begin() + 2, frame.end(), kSync0) == frame.end()) return frame;
  }
}

}  // namespace

TEST_CASE("CRC-16/CCITT-FALSE matches its published check value", "[magnetometer_bridge][components][bridge]") {
  const std::uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  CHECK(crc16CcittFalse(check) == 0x29B1);  // the catalogue's check value for "123456789"
}

TEST_CASE("a frame round-trips through the parser, byte by byte", "[magnetometer_bridge][components][bridge]") {
  const FieldSample sample{7, {-21000, 1500, 43000}};
  FrameParser parser;
  std::optional<FieldSample> out;
  for (std::uint8_t byte : encodeFrame(sample)) {
    REQUIRE_FALSE(out);
    out = parser.push(byte);
  }
  REQUIRE(out);
  CHECK(out->sequence == 7);
  CHECK(out->b_nT == sample.b_nT);
}

TEST_CASE("10^4 corrupted frames among good ones: no bad sample, exact counts",
          "[magnetometer_bridge][components][bridge]") {
  std::mt19937 rng(2026);
  std::uint32_t sequence = 0;
  std::vector<std::uint8_t> stream;
  std::vector<FieldSample> good;
  std::uint64_t bad_crc = 0, bad_header = 0, noise = 0;
  std::uniform_int_distribution<int> kind(0, 4), noise_byte(0, 255), length(1, 40);
  const int corrupted = 10000;
  for (int i = 0; i < corrupted; ++i) {
    FieldSample sample;
    auto frame = cleanFrame(rng, sequence, sample);
    stream.insert(stream.end(), frame.begin(), frame.end());
    good.push_back(sample);
    auto bad = cleanFrame(rng, sequence, sample);
    switch (kind(rng)) {
      case 0:  // a flipped payload bit
        bad[9] ^= 0x10;
        if (bad[9] == kSync0) bad[9] ^= 0x01;
        ++bad_crc;
        break;
      case 1:  // wrong length byte
        bad[3] = 15;
        ++bad_header;
        break;
      case 2:  // unknown type
        bad[2] = 0x02;
        ++bad_header;
        break;
      case 3:  // CRC bytes lost on the line
        bad[21] = bad[20] = 0;
        ++bad_crc;
        break;
      default: {  // line noise without a sync byte
        const int n = length(rng);
        for (int b = 0; b < n; ++b) {
          int v = noise_byte(rng);
          stream.push_back(static_cast<std::uint8_t>(v == kSync0 ? 0 : v));
        }
        noise += static_cast<std::uint64_t>(n);
        continue;
      }
    }
    // A bad CRC could, by chance, be the right one: re-check.
    if (bad[2] == kTypeFieldSample && bad[3] == kPayloadLength &&
        crc16CcittFalse(std::span(bad).subspan(2, 18)) == (bad[20] | bad[21] << 8)) {
      --bad_crc;
      good.push_back(sample);
    }
    stream.insert(stream.end(), bad.begin(), bad.end());
  }
  FrameParser parser;
  std::vector<FieldSample> delivered;
  for (std::uint8_t byte : stream) {
    if (auto sample = parser.push(byte)) delivered.push_back(*sample);
  }
  REQUIRE(delivered.size() == good.size());
  for (std::size_t i = 0; i < good.size(); ++i) {
    CHECK(delivered[i].sequence == good[i].sequence);
    CHECK(delivered[i].b_nT == good[i].b_nT);
  }
  CHECK(parser.counts().frames == good.size());
  CHECK(parser.counts().bad_crc == bad_crc);
  CHECK(parser.counts().bad_header == bad_header);
  // Each rejected candidate leaves its 21 remaining bytes, none a sync, as
  // skipped bytes; noise is skipped byte for byte.
  CHECK(parser.counts().skipped_bytes == noise + (bad_crc + bad_header) * (kFrameSize - 1));
}
