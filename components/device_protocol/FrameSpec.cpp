// SPDX-License-Identifier: Apache-2.0
#include "components/device_protocol/FrameSpec.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace flatsat::device_protocol {
namespace {

std::string byteRange(std::size_t from, std::size_t to) {
  return "bytes " + std::to_string(from) + ".." + std::to_string(to - 1);
}

/// The range of whole counts a type holds; a float type, the values it holds exactly (a
/// header constant is compared as it arrives).
bool fitsType(FieldType type, double value) {
  if (!std::isfinite(value)) return false;
  if (type == FieldType::kF64) return true;
  if (type == FieldType::kF32) {
    return std::abs(value) <= std::numeric_limits<float>::max() && static_cast<double>(static_cast<float>(value)) == value;
  }
  if (value != std::floor(value)) return false;
  const double bits = 8.0 * static_cast<double>(fieldBytes(type));
  const double lowest = isSigned(type) ? -std::pow(2.0, bits - 1) : 0.0;
  const double highest = isSigned(type) ? std::pow(2.0, bits - 1) - 1 : std::pow(2.0, bits) - 1;
  return value >= lowest && value <= highest;
}

}  // namespace

std::optional<FieldType> fieldTypeFromName(const std::string& name) {
  static const std::map<std::string, FieldType> kTypes = {
      {"u8", FieldType::kU8},   {"i8", FieldType::kI8},   {"u16", FieldType::kU16}, {"i16", FieldType::kI16},
      {"u32", FieldType::kU32}, {"i32", FieldType::kI32}, {"f32", FieldType::kF32}, {"f64", FieldType::kF64}};
  const auto found = kTypes.find(name);
  if (found == kTypes.end()) return std::nullopt;
  return found->second;
}

std::size_t fieldBytes(FieldType type) {
  switch (type) {
    case FieldType::kU8:
    case FieldType::kI8: return 1;
    case FieldType::kU16:
    case FieldType::kI16: return 2;
    case FieldType::kU32:
    case FieldType::kI32:
    case FieldType::kF32: return 4;
    case FieldType::kF64: return 8;
  }
  return 0;
}

std::optional<std::size_t> FrameSpec::fieldFor(const std::string& maps_to) const {
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (fields[i].maps_to == maps_to) return i;
  }
  return std::nullopt;
}

std::optional<std::size_t> FrameSpec::sequenceField() const {
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (fields[i].sequence) return i;
  }
  return std::nullopt;
}

bool isInteger(FieldType type) { return type != FieldType::kF32 && type != FieldType::kF64; }

bool isSigned(FieldType type) { return type == FieldType::kI8 || type == FieldType::kI16 || type == FieldType::kI32; }

std::vector<SpecProblem> FrameSpec::validate() const {
  std::vector<SpecProblem> problems;
  if (sync.empty()) problems.push_back({-1, "sync", "at least one byte"});
  for (const std::string& error : checksum.validate()) {
    problems.push_back({-1, "checksum", error});
  }
  // Offsets first: the byte map below is sized by them.
  const auto beyond = [](std::size_t at, std::size_t bytes) { return at > kMaxFrameBytes || bytes > kMaxFrameBytes - at; };
  bool bounded = !beyond(0, sync.size()) && checksum.bytes() > 0 && !beyond(checksum_at, static_cast<std::size_t>(checksum.bytes()));
  if (!bounded) problems.push_back({-1, "checksum", "the frame must end within " + std::to_string(kMaxFrameBytes) + " bytes"});
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (beyond(fields[i].at, fieldBytes(fields[i].type))) {
      problems.push_back({static_cast<int>(i), "at", "beyond the longest frame, " + std::to_string(kMaxFrameBytes) + " bytes"});
      bounded = false;
    }
  }
  if (!bounded) return problems;
  // Who owns each byte: the sync, a field, or the check; none twice, none left out.
  const std::size_t total = size();
  std::vector<int> owner(total, -3);  // -3 nobody, -2 sync, -1 check, >= 0 a field
  const auto claim = [&](std::size_t from, std::size_t to, int who, int field, const std::string& what) {
    for (std::size_t b = from; b < to && b < total; ++b) {
      if (owner[b] != -3) {
        const std::string other = owner[b] == -2   ? "the sync"
                                  : owner[b] == -1 ? "the checksum"
                                                   : "field '" + fields[static_cast<std::size_t>(owner[b])].name + "'";
        problems.push_back({field, field < 0 ? "checksum" : "at", what + " (" + byteRange(from, to) + ") overlaps " + other});
        return;
      }
      owner[b] = who;
    }
  };
  claim(0, sync.size(), -2, -1, "the sync");
  std::set<std::string> names;
  std::set<std::string> published;
  int counters = 0;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const FieldSpec& f = fields[i];
    const int index = static_cast<int>(i);
    if (f.name.empty() || !names.insert(f.name).second) {
      problems.push_back({index, "name", "'" + f.name + "' is empty or named twice in this frame"});
    }
    if (f.end() > checksum_at) {
      problems.push_back({index, "at", "field '" + f.name + "' (" + byteRange(f.at, f.end()) + ") runs into the checksum at byte " +
                                           std::to_string(checksum_at)});
    }
    claim(f.at, f.end(), index, index, "field '" + f.name + "'");
    if (f.constant && !fitsType(f.type, *f.constant)) {
      problems.push_back({index, "const", "does not fit the field's type"});
    }
    if (!std::isfinite(f.scale) || f.scale == 0.0) problems.push_back({index, "scale", "must be finite and non-zero"});
    if (f.full_scale && !(std::isfinite(*f.full_scale) && *f.full_scale > 0.0)) {
      problems.push_back({index, "full_scale", "must be finite and > 0"});
    }
    if (f.sequence && (!isInteger(f.type) || isSigned(f.type))) {
      problems.push_back({index, "sequence", "a sample counter must be an unsigned integer (u8, u16, u32)"});
    }
    if (f.sequence && ++counters > 1) problems.push_back({index, "sequence", "a frame has one sample counter"});
    if (!f.maps_to.empty() && !published.insert(f.maps_to).second) {
      problems.push_back({index, "to", "'" + f.maps_to + "' is carried by another field too"});
    }
    if (f.constant && (f.sequence || !f.maps_to.empty())) {
      problems.push_back({index, "const", "a header constant is neither a counter nor published"});
    }
  }
  claim(checksum_at, total, -1, -1, "the checksum");
  for (std::size_t b = 0; b < total; ++b) {
    if (owner[b] == -3) {
      problems.push_back({-1, "fields", "byte " + std::to_string(b) + " belongs to no field (declare padding as a field)"});
      break;
    }
  }
  if (covers_to != checksum_at || (covers_from != 0 && covers_from != sync.size())) {
    problems.push_back({-1, "checksum", "covers " + byteRange(covers_from, covers_to) + ": it must cover every byte from " +
                                            std::to_string(sync.size()) + " (or 0) up to the checksum at " +
                                            std::to_string(checksum_at)});
  }
  return problems;
}

}  // namespace flatsat::device_protocol
