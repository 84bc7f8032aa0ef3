// SPDX-License-Identifier: Apache-2.0
#include "components/device_protocol/Checksum.hpp"

namespace flatsat::device_protocol {
namespace {

std::uint32_t reflectBits(std::uint32_t value, int bits) {
  std::uint32_t out = 0;
  for (int i = 0; i < bits; ++i) {
    if (value & (1u << i)) out |= 1u << (bits - 1 - i);
  }
  return out;
}

std::uint32_t widthMask(int bits) { return bits >= 32 ? 0xFFFFFFFFu : (1u << bits) - 1u; }

std::string hexText(std::uint32_t value) {
  static const char* digits = "0123456789ABCDEF";
  std::string text;
  do {
    text.insert(text.begin(), digits[value & 0xF]);
    value >>= 4;
  } while (value != 0);
  return "0x" + text;
}

}  // namespace

std::optional<ChecksumSpec::Kind> checksumKindFromName(const std::string& name) {
  if (name == "crc") return ChecksumSpec::Kind::kCrc;
  if (name == "sum8") return ChecksumSpec::Kind::kSum8;
  if (name == "xor8") return ChecksumSpec::Kind::kXor8;
  return std::nullopt;
}

std::vector<std::string> ChecksumSpec::validate() const {
  std::vector<std::string> errors;
  if (kind != Kind::kCrc) {
    if (width_bits != 8) errors.push_back("width_bits: " + std::to_string(width_bits) + " must be 8 for sum8 and xor8");
    if (init > 0xFFu) errors.push_back("init: " + hexText(init) + " does not fit 8 bits");
    if (xor_out > 0xFFu) errors.push_back("xor_out: " + hexText(xor_out) + " does not fit 8 bits");
    return errors;
  }
  if (width_bits != 8 && width_bits != 16 && width_bits != 32) {  // also keeps bytes() > 0
    errors.push_back("width_bits: " + std::to_string(width_bits) + " must be 8, 16 or 32");
    return errors;
  }
  if ((poly & 1u) == 0 || poly > widthMask(width_bits)) {
    errors.push_back("poly: " + hexText(poly) + " must be odd and fit " + std::to_string(width_bits) + " bits");
  }
  if (init > widthMask(width_bits)) errors.push_back("init: " + hexText(init) + " does not fit " + std::to_string(width_bits) + " bits");
  if (xor_out > widthMask(width_bits)) {
    errors.push_back("xor_out: " + hexText(xor_out) + " does not fit " + std::to_string(width_bits) + " bits");
  }
  return errors;
}

std::uint32_t computeChecksum(const ChecksumSpec& spec, std::span<const std::uint8_t> bytes) {
  if (spec.kind == ChecksumSpec::Kind::kSum8 || spec.kind == ChecksumSpec::Kind::kXor8) {
    // init and xor_out as for a CRC: "~sum" devices send the sum's complement (xor_out 0xFF).
    std::uint32_t value = spec.init;
    for (const std::uint8_t byte : bytes) value = spec.kind == ChecksumSpec::Kind::kSum8 ? value + byte : value ^ byte;
    return (value ^ spec.xor_out) & 0xFFu;
  }
  // Bit by bit, most significant first: a few dozen bytes per frame at serial rates.
  const int width = spec.width_bits;
  const std::uint32_t top = 1u << (width - 1);
  std::uint32_t crc = spec.init;
  for (const std::uint8_t byte : bytes) {
    const std::uint32_t in = spec.reflect_in ? reflectBits(byte, 8) : byte;
    crc ^= in << (width - 8);
    for (int bit = 0; bit < 8; ++bit) crc = (crc & top) ? (crc << 1) ^ spec.poly : crc << 1;
    crc &= widthMask(width);
  }
  if (spec.reflect_out) crc = reflectBits(crc, width);
  return (crc ^ spec.xor_out) & widthMask(width);
}

}  // namespace flatsat::device_protocol
