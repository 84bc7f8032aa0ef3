// SPDX-License-Identifier: Apache-2.0
#pragma once
// The serial protocol of the rig's reference magnetometer (a real-style
// three-axis fluxgate/AMR unit with a binary streaming output), spoken by
// the magnetometer bridge and by its device simulator.
//
// Frame, little-endian, 22 bytes, at 115200 baud 8N1, one per sample:
//   offset size field
//   0      2    sync 0xAA 0x55
//   2      1    type: 0x01 = field sample
//   3      1    payload length: 16
//   4      4    sequence number, uint32, +1 per sample (wraps)
//   8      4    Bx, int32 [nT], sensor axes
//   12     4    By, int32 [nT]
//   16     4    Bz, int32 [nT]
//   20     2    CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF) over bytes 2..19
// A frame whose length, type or CRC is wrong is dropped and counted; the
// parser then resynchronises on the next sync pattern.
#include <array>
#include <cstdint>
#include <optional>
#include <span>

namespace flatsat::magnetometer_bridge {

inline constexpr std::size_t kFrameSize = 22;
inline constexpr std::uint8_t kSync0 = 0xAA, kSync1 = 0x55;
inline constexpr std::uint8_t kTypeFieldSample = 0x01;
inline constexpr std::uint8_t kPayloadLength = 16;

struct FieldSample {
  std::uint32_t sequence = 0;
  std::array<std::int32_t, 3> b_nT{};  // [nT] sensor axes
};

std::uint16_t crc16CcittFalse(std::span<const std::uint8_t> bytes);
std::array<std::uint8_t, kFrameSize> encodeFrame(const FieldSample& sample);

/// What a parser has seen so far.
struct ParserCounts {
  std::uint64_t frames = 0;        // good frames delivered
  std::uint64_t bad_crc = 0;       // well-formed header, CRC mismatch
  std::uint64_t bad_header = 0;    // sync found, but wrong type or length
  std::uint64_t skipped_bytes = 0; // bytes discarded while searching for sync
};

/// Streaming parser: feed bytes as they come off the port; whole, valid
/// frames come out. Never allocates; any byte sequence is safe.
class FrameParser {
 public:
  /// Consumes one byte; returns a sample when it completes a valid frame.
  std::optional<FieldSample> push(std::uint8_t byte);
  const ParserCounts& counts() const { return counts_; }

 private:
  void dropFirst(std::size_t n);

  std::array<std::uint8_t, kFrameSize> buffer_{};
  std::size_t size_ = 0;
  ParserCounts counts_;
};

}  // namespace flatsat::magnetometer_bridge
