// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstddef>
#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "components/device_protocol/Checksum.hpp"

namespace flatsat::device_protocol {

/// The longest frame a description may give [bytes]: offsets beyond it are refused
/// before any arithmetic on them.
inline constexpr std::size_t kMaxFrameBytes = 1024;

/// Wire types of a frame's fields. 64-bit integers are left out: a field's value travels
/// as a double, exact up to 2^53.
enum class FieldType { kU8, kI8, kU16, kI16, kU32, kI32, kF32, kF64 };

/// "u8", "i8", "u16", "i16", "u32", "i32", "f32", "f64" → type; nullopt for anything else.
std::optional<FieldType> fieldTypeFromName(const std::string& name);
std::size_t fieldBytes(FieldType type);
bool isInteger(FieldType type);
bool isSigned(FieldType type);

/// One field of a frame: where it sits, how it is coded, and what it means.
struct FieldSpec {
  std::string name;                       // unique in its frame
  std::size_t at = 0;                     // [byte] offset from the frame's first sync byte
  FieldType type = FieldType::kU8;
  bool little_endian = true;
  std::optional<double> constant;         // header value: a frame without it is refused (bad header)
  bool sequence = false;                  // the device's sample counter, unsigned: gaps are counted modulo its range
  double scale = 1.0;                     // [unit of `maps_to` per count], finite, non-zero
  std::string maps_to;                    // the topic field it carries ("" : decoded, not published)
  std::optional<double> full_scale;       // [unit of `maps_to`] the device's range, > 0: a value there is saturated

  std::size_t end() const { return at + fieldBytes(type); }
};

/// A problem of a frame description: at field `field` (an index into fields), or at the
/// frame itself (field < 0), under `key`.
struct SpecProblem {
  int field = -1;
  std::string key;
  std::string reason;
};

/// A fixed-length binary frame: sync bytes at offset 0, fields, then a check over a
/// byte range that must be everything between the sync and the check (a check that
/// leaves bytes out lets a corrupted field through).
struct FrameSpec {
  std::string name;
  std::vector<std::uint8_t> sync;         // >= 1 byte, at offset 0
  std::vector<FieldSpec> fields;
  ChecksumSpec checksum;
  std::size_t checksum_at = 0;            // [byte] offset of the check
  bool checksum_little_endian = true;
  std::size_t covers_from = 0;            // [byte] first byte the check covers: 0 or sync.size()
  std::size_t covers_to = 0;              // [byte] one past the last: checksum_at

  std::size_t size() const { return checksum_at + static_cast<std::size_t>(std::max(checksum.bytes(), 0)); }
  /// The field that carries topic field `maps_to`, or the sample counter; nullopt: none.
  std::optional<std::size_t> fieldFor(const std::string& maps_to) const;
  std::optional<std::size_t> sequenceField() const;
  /// Every problem; empty when the frame is well formed: at most kMaxFrameBytes; every
  /// byte is sync, one field or the check, none twice; constants fit their type exactly;
  /// a counter is unsigned; the check covers the frame.
  std::vector<SpecProblem> validate() const;
};

}  // namespace flatsat::device_protocol
