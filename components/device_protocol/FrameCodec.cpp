// SPDX-License-Identifier: Apache-2.0
#include "components/device_protocol/FrameCodec.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <span>

namespace flatsat::device_protocol {
namespace {

std::uint64_t readUnsigned(const std::uint8_t* at, std::size_t n, bool little_endian) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = little_endian ? n - 1 - i : i;
    value = (value << 8) | at[k];
  }
  return value;
}

void writeUnsigned(std::uint8_t* at, std::size_t n, bool little_endian, std::uint64_t value) {
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = little_endian ? i : n - 1 - i;
    at[k] = static_cast<std::uint8_t>(value >> (8 * i));
  }
}

/// An integer count held to its type's range (what a device's firmware saturates to).
std::uint64_t integerBits(FieldType type, double value) {
  const std::size_t n = fieldBytes(type);
  const bool is_signed = type == FieldType::kI8 || type == FieldType::kI16 || type == FieldType::kI32;
  const double bits = 8.0 * static_cast<double>(n);
  const double lowest = is_signed ? -std::ldexp(1.0, static_cast<int>(bits) - 1) : 0.0;
  const double highest = is_signed ? std::ldexp(1.0, static_cast<int>(bits) - 1) - 1.0 : std::ldexp(1.0, static_cast<int>(bits)) - 1.0;
  const double count = std::isfinite(value) ? std::clamp(std::nearbyint(value), lowest, highest) : 0.0;
  return static_cast<std::uint64_t>(static_cast<std::int64_t>(count));
}

}  // namespace

double decodeField(const FieldSpec& field, const std::uint8_t* frame) {
  const std::size_t n = fieldBytes(field.type);
  const std::uint64_t bits = readUnsigned(frame + field.at, n, field.little_endian);
  switch (field.type) {
    case FieldType::kU8:
    case FieldType::kU16:
    case FieldType::kU32: return static_cast<double>(bits);
    case FieldType::kI8: return static_cast<double>(static_cast<std::int8_t>(bits));
    case FieldType::kI16: return static_cast<double>(static_cast<std::int16_t>(bits));
    case FieldType::kI32: return static_cast<double>(static_cast<std::int32_t>(bits));
    case FieldType::kF32: return static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(bits)));
    case FieldType::kF64: return std::bit_cast<double>(bits);
  }
  return 0.0;
}

std::vector<std::uint8_t> encodeFrame(const FrameSpec& spec, const RawValues& raw) {
  if (raw.size() != spec.fields.size()) {
    throw std::invalid_argument("encodeFrame: " + std::to_string(raw.size()) + " values for " +
                                std::to_string(spec.fields.size()) + " fields of frame '" + spec.name + "'");
  }
  std::vector<std::uint8_t> frame(spec.size(), 0);
  std::copy(spec.sync.begin(), spec.sync.end(), frame.begin());
  for (std::size_t i = 0; i < spec.fields.size(); ++i) {
    const FieldSpec& f = spec.fields[i];
    const double value = f.constant ? *f.constant : raw[i];
    std::uint64_t bits = 0;
    if (f.type == FieldType::kF32) {
      constexpr double kFloatMax = std::numeric_limits<float>::max();
      const double held = std::isfinite(value) ? std::clamp(value, -kFloatMax, kFloatMax) : value;
      bits = std::bit_cast<std::uint32_t>(static_cast<float>(held));
    } else if (f.type == FieldType::kF64) {
      bits = std::bit_cast<std::uint64_t>(value);
    } else {
      bits = integerBits(f.type, value);
    }
    writeUnsigned(&frame[f.at], fieldBytes(f.type), f.little_endian, bits);
  }
  const std::uint32_t check =
      computeChecksum(spec.checksum, std::span(frame).subspan(spec.covers_from, spec.covers_to - spec.covers_from));
  writeUnsigned(&frame[spec.checksum_at], static_cast<std::size_t>(spec.checksum.bytes()), spec.checksum_little_endian,
                check);
  return frame;
}

FrameParser::FrameParser(FrameSpec spec) : spec_(std::move(spec)), values_(spec_.fields.size()) {
  if (const auto problems = spec_.validate(); !problems.empty()) {
    throw std::invalid_argument("FrameParser: frame '" + spec_.name + "': " + problems.front().key + ": " +
                                problems.front().reason);
  }
  buffer_.resize(spec_.size());
  for (std::size_t i = 0; i < spec_.fields.size(); ++i) {
    if (spec_.fields[i].constant) header_fields_.push_back(i);
  }
  std::sort(header_fields_.begin(), header_fields_.end(),
            [this](std::size_t a, std::size_t b) { return spec_.fields[a].at < spec_.fields[b].at; });
}

void FrameParser::dropFirst(std::size_t n) {
  std::memmove(buffer_.data(), buffer_.data() + n, size_ - n);
  size_ -= n;
}

bool FrameParser::headerBroken() const {
  for (const std::size_t i : header_fields_) {
    const FieldSpec& f = spec_.fields[i];
    if (size_ < f.end()) return false;  // judged when its bytes are in
    if (decodeField(f, buffer_.data()) != *f.constant) return true;
  }
  return false;
}

std::optional<RawValues> FrameParser::push(std::uint8_t byte) {
  buffer_[size_++] = byte;
  const std::vector<std::uint8_t>& sync = spec_.sync;
  // After a rejected candidate the buffer may already hold the next frame,
  // so keep going until the bytes held need more input.
  for (;;) {
    std::size_t junk = 0;  // line noise before the sync pattern
    while (junk < size_ && buffer_[junk] != sync[0]) ++junk;
    if (junk > 0) {
      dropFirst(junk);
      counts_.skipped_bytes += junk;
    }
    const std::size_t held_sync = std::min(size_, sync.size());
    if (!std::equal(sync.begin() + 1, sync.begin() + static_cast<std::ptrdiff_t>(std::max<std::size_t>(held_sync, 1)),
                    buffer_.begin() + 1)) {
      dropFirst(1);
      ++counts_.skipped_bytes;
      continue;
    }
    if (headerBroken()) {
      ++counts_.bad_header;
      dropFirst(1);  // the rest may hold the next frame's sync
      continue;
    }
    if (size_ < buffer_.size()) return std::nullopt;
    const std::uint32_t check = computeChecksum(
        spec_.checksum, std::span(buffer_).subspan(spec_.covers_from, spec_.covers_to - spec_.covers_from));
    const std::uint64_t sent = readUnsigned(&buffer_[spec_.checksum_at], static_cast<std::size_t>(spec_.checksum.bytes()),
                                            spec_.checksum_little_endian);
    if (check != sent) {
      ++counts_.bad_checksum;
      dropFirst(1);
      continue;
    }
    bool finite = true;
    for (std::size_t i = 0; i < spec_.fields.size(); ++i) {
      values_[i] = decodeField(spec_.fields[i], buffer_.data());
      finite = finite && std::isfinite(values_[i]);
    }
    size_ = 0;
    if (!finite) {
      // A device that sends NaN with a good check is faulty, not noisy: the frame is
      // whole, so nothing in it can start another.
      ++counts_.bad_value;
      return std::nullopt;
    }
    ++counts_.frames;
    return values_;
  }
}

}  // namespace flatsat::device_protocol
