// SPDX-License-Identifier: Apache-2.0
#include "components/magnetometer_bridge/MagnetometerFrame.hpp"

#include <algorithm>
#include <cstring>

namespace flatsat::magnetometer_bridge {

namespace {

void putU32(std::uint8_t* out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

std::uint32_t getU32(const std::uint8_t* in) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(in[i]) << (8 * i);
  return v;
}

}  // namespace

std::uint16_t crc16CcittFalse(std::span<const std::uint8_t> bytes) {
  std::uint16_t crc = 0xFFFF;
  for (std::uint8_t byte : bytes) {
    crc ^= static_cast<std::uint16_t>(byte << 8);
    for (int bit = 0; bit < 8; ++bit) {
      crc = (crc & 0x8000) ? static_cast<std::uint16_t>((crc << 1) ^ 0x1021)
                           : static_cast<std::uint16_t>(crc << 1);
    }
  }
  return crc;
}

std::array<std::uint8_t, kFrameSize> encodeFrame(const FieldSample& sample) {
  std::array<std::uint8_t, kFrameSize> frame{};
  frame[0] = kSync0;
  frame[1] = kSync1;
  frame[2] = kTypeFieldSample;
  frame[3] = kPayloadLength;
  putU32(&frame[4], sample.sequence);
  for (int axis = 0; axis < 3; ++axis) {
    putU32(&frame[8 + 4 * axis], static_cast<std::uint32_t>(sample.b_nT[axis]));
  }
  const std::uint16_t crc = crc16CcittFalse(std::span(frame).subspan(2, 18));
  frame[20] = static_cast<std::uint8_t>(crc & 0xFF);
  frame[21] = static_cast<std::uint8_t>(crc >> 8);
  return frame;
}

void FrameParser::dropFirst(std::size_t n) {
  std::memmove(buffer_.data(), buffer_.data() + n, size_ - n);
  size_ -= n;
}

std::optional<FieldSample> FrameParser::push(std::uint8_t byte) {
  buffer_[size_++] = byte;
  // After a rejected candidate the buffer may already hold the next frame,
  // so keep going until the bytes held need more input.
  for (;;) {
    std::size_t junk = 0;  // line noise before the sync pattern
    while (junk < size_ && buffer_[junk] != kSync0) ++junk;
    if (junk > 0) {
      dropFirst(junk);
      counts_.skipped_bytes += junk;
    }
    if (size_ >= 2 && buffer_[1] != kSync1) {
      dropFirst(1);
      ++counts_.skipped_bytes;
      continue;
    }
    if (size_ >= 4 && (buffer_[2] != kTypeFieldSample || buffer_[3] != kPayloadLength)) {
      ++counts_.bad_header;
      dropFirst(1);  // the rest may hold the next frame's sync
      continue;
    }
    if (size_ < kFrameSize) return std::nullopt;
    const std::uint16_t crc = crc16CcittFalse(std::span(buffer_).subspan(2, 18));
    if ((crc & 0xFF) != buffer_[20] || (crc >> 8) != buffer_[21]) {
      ++counts_.bad_crc;
      dropFirst(1);
      continue;
    }
    FieldSample sample;
    sample.sequence = getU32(&buffer_[4]);
    for (int axis = 0; axis < 3; ++axis) {
      sample.b_nT[axis] = static_cast<std::int32_t>(getU32(&buffer_[8 + 4 * axis]));
    }
    size_ = 0;
    ++counts_.frames;
    return sample;
  }
}

}  // namespace flatsat::magnetometer_bridge
