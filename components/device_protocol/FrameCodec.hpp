// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "components/device_protocol/FrameSpec.hpp"

namespace flatsat::device_protocol {

/// A frame's field values in wire counts, in the order of FrameSpec::fields.
using RawValues = std::vector<double>;

/// What a parser has seen so far.
struct ParserCounts {
  std::uint64_t frames = 0;         // good frames delivered
  std::uint64_t bad_checksum = 0;   // whole frame, check mismatch
  std::uint64_t bad_header = 0;     // sync found, but a header constant wrong
  std::uint64_t bad_value = 0;      // check passed, but a float field not finite
  std::uint64_t skipped_bytes = 0;  // bytes discarded while searching for sync
};

/// Streaming parser for one frame description: feed bytes as they come off the line,
/// whole valid frames come out. A candidate with a wrong header or check drops one byte
/// and the search goes on from the next, so a frame that starts inside a corrupted one is
/// still found. A frame whose check passes but which carries a non-finite float is a
/// faulty device's, whole: it is dropped entire and counted (bad_value).
/// Allocates only for the values of a frame it delivers; any byte sequence is safe.
class FrameParser {
 public:
  /// @throws std::invalid_argument when the spec is not valid (FrameSpec::validate()).
  explicit FrameParser(FrameSpec spec);

  /// Consumes one byte; returns the field values when it completes a valid frame.
  std::optional<RawValues> push(std::uint8_t byte);
  const ParserCounts& counts() const { return counts_; }

 private:
  void dropFirst(std::size_t n);
  bool headerBroken() const;

  FrameSpec spec_;
  std::vector<std::size_t> header_fields_;  // constant fields, by offset
  std::vector<std::uint8_t> buffer_;
  std::size_t size_ = 0;
  RawValues values_;
  ParserCounts counts_;
};

/// The bytes of one frame: sync, each field from `raw` (header constants from the spec;
/// integers rounded to the nearest count and held to their type's range, f32 held to
/// ±FLT_MAX), the check. @throws std::invalid_argument unless `raw` has one value per field.
std::vector<std::uint8_t> encodeFrame(const FrameSpec& spec, const RawValues& raw);

/// One field's value read from a whole frame.
double decodeField(const FieldSpec& field, const std::uint8_t* frame);

}  // namespace flatsat::device_protocol
