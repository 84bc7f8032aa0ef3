// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace flatsat::device_protocol {

/// A frame's check. CRCs in the Rocksoft model (Williams, "A painless guide to CRC error
/// detection algorithms", 1993, ch. 15): the parameters the CRC catalogues list, so a
/// device's data sheet maps onto it field by field.
struct ChecksumSpec {
  enum class Kind { kCrc, kSum8, kXor8 };
  Kind kind = Kind::kCrc;
  int width_bits = 16;           // [-] CRC: 8, 16 or 32; sum8 and xor8: 8
  std::uint32_t poly = 0x1021;   // [-] CRC only: generator, normal form, top bit left out; odd
  std::uint32_t init = 0xFFFF;   // [-] register before the first byte (sum8, xor8: the start value), < 2^width
  bool reflect_in = false;       // [-] CRC only: bytes enter least significant bit first
  bool reflect_out = false;      // [-] CRC only: the register is reflected before xor_out
  std::uint32_t xor_out = 0;     // [-] xored into the result (also sum8, xor8), < 2^width

  int bytes() const { return width_bits / 8; }
  /// Every violation as "key: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// "crc", "sum8", "xor8" → kind; nullopt for anything else.
std::optional<ChecksumSpec::Kind> checksumKindFromName(const std::string& name);

/// The check of `bytes`, in the low `width_bits` bits.
std::uint32_t computeChecksum(const ChecksumSpec& spec, std::span<const std::uint8_t> bytes);

}  // namespace flatsat::device_protocol
