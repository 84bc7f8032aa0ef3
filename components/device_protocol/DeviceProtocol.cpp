// SPDX-License-Identifier: Apache-2.0
#include "bus/InstallPaths.hpp"
#include "components/device_protocol/DeviceProtocol.hpp"

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

namespace flatsat::device_protocol {
namespace {

/// "AA 55" → {0xAA, 0x55}: bytes as a data sheet writes them, two hex digits each.
std::optional<std::vector<std::uint8_t>> hexBytes(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::istringstream words(text);
  std::string word;
  while (words >> word) {
    if (word.size() != 2 || !std::isxdigit(static_cast<unsigned char>(word[0])) ||
        !std::isxdigit(static_cast<unsigned char>(word[1]))) {
      return std::nullopt;
    }
    out.push_back(static_cast<std::uint8_t>(std::stoul(word, nullptr, 16)));
  }
  return out;
}

/// An integer as a data sheet writes it, decimal or hex ("0x1021", "-3"), within
/// [lowest, highest]; problems at `key`.
template <class Integer>
void readWord(bus::ParamReader& reader, const std::string& key, Integer& value, long long lowest, long long highest) {
  if (!reader.has(key)) return;
  std::string text;
  reader.read(key, text);
  const bool negative = !text.empty() && text[0] == '-';
  const std::string digits = negative ? text.substr(1) : text;
  const bool hex = digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X');
  char* end = nullptr;
  errno = 0;
  const unsigned long long magnitude = std::strtoull(digits.c_str() + (hex ? 2 : 0), &end, hex ? 16 : 10);
  const bool whole = !digits.empty() && end != nullptr && *end == '\0' && errno == 0 &&
                     std::isxdigit(static_cast<unsigned char>(digits[hex ? 2 : 0])) && magnitude <= (1ULL << 32);
  const long long parsed = negative ? -static_cast<long long>(magnitude) : static_cast<long long>(magnitude);
  if (!whole || parsed < lowest || parsed > highest) {
    return reader.problem(key, "'" + text + "' is not an integer in " + std::to_string(lowest) + ".." + std::to_string(highest) +
                                   " (decimal, or hex as 0x1021)");
  }
  value = static_cast<Integer>(parsed);
}

/// byte_order: little | big, at `key` of `reader`.
void readByteOrder(bus::ParamReader& reader, bool& little_endian) {
  std::string order = little_endian ? "little" : "big";
  reader.read("byte_order", order);
  if (order != "little" && order != "big") reader.problem("byte_order", "'" + order + "' is neither little nor big");
  little_endian = order == "little";
}

void readChecksum(bus::ParamReader& c, FrameSpec& frame) {
  std::string kind = "crc";
  c.read("kind", kind);
  if (const auto parsed = checksumKindFromName(kind)) {
    frame.checksum.kind = *parsed;
  } else {
    c.problem("kind", "'" + kind + "' is not crc, sum8 or xor8");
  }
  constexpr long long kWord = 0xFFFFFFFFLL;
  if (frame.checksum.kind != ChecksumSpec::Kind::kCrc) {
    frame.checksum.width_bits = 8;
    frame.checksum.init = 0;
    for (const char* key : {"poly", "reflect_in", "reflect_out"}) {
      if (c.has(key)) c.problem(key, "a CRC's parameter: " + kind + " has none");
    }
    c.leave({"poly", "reflect_in", "reflect_out"});  // reported above, not again as unknown
  } else {
    readWord(c, "poly", frame.checksum.poly, 0, kWord);
    c.read("reflect_in", frame.checksum.reflect_in);
    c.read("reflect_out", frame.checksum.reflect_out);
  }
  c.read("width_bits", frame.checksum.width_bits);
  readWord(c, "init", frame.checksum.init, 0, kWord);
  readWord(c, "xor_out", frame.checksum.xor_out, 0, kWord);
  std::uint64_t at = 0, from = 0;
  c.read("at", at);
  c.read("covers_from", from);
  frame.checksum_at = frame.covers_to = static_cast<std::size_t>(at);
  frame.covers_from = static_cast<std::size_t>(from);
  frame.checksum_little_endian = true;
  readByteOrder(c, frame.checksum_little_endian);
  // A catalogue check value ("123456789"), when the data sheet gives one: a transcribed
  // polynomial or init that is wrong is caught here, not on the bench.
  if (c.has("check")) {
    std::uint32_t check = 0;
    readWord(c, "check", check, 0, kWord);
    const std::string digits = "123456789";
    const std::vector<std::uint8_t> text(digits.begin(), digits.end());
    if (frame.checksum.validate().empty() && computeChecksum(frame.checksum, text) != check) {
      c.problem("check", "the parameters give another check value for \"123456789\": poly, init, reflection or "
                         "xor_out is not the data sheet's");
    }
  }
}

FieldSpec readField(bus::ParamReader& f, const std::string& topic, bool frame_little_endian, const FieldUnitLookup& unit_of) {
  FieldSpec field;
  field.little_endian = frame_little_endian;
  f.read("name", field.name);
  std::uint64_t at = 0;
  f.read("at", at);
  field.at = static_cast<std::size_t>(at);
  std::string type = "u8";
  f.read("type", type);
  if (const auto parsed = fieldTypeFromName(type)) {
    field.type = *parsed;
  } else {
    f.problem("type", "'" + type + "' is not u8, i8, u16, i16, u32, i32, f32 or f64");
  }
  readByteOrder(f, field.little_endian);
  if (f.has("const") && isInteger(field.type)) {
    long long constant = 0;
    readWord(f, "const", constant, -(1LL << 31), 0xFFFFFFFFLL);  // its type's range: FrameSpec::validate
    field.constant = static_cast<double>(constant);
  } else if (f.has("const")) {
    double constant = 0.0;
    f.read("const", constant, "-");
    field.constant = constant;
  }
  f.read("sequence", field.sequence);
  f.read("to", field.maps_to);
  if (!field.maps_to.empty()) {
    const auto unit = unit_of(topic, field.maps_to);
    if (!unit) {
      f.problem("to", "'" + field.maps_to + "' is not a field of " + topic);
    } else {
      // The scale is "counts to the topic field's unit": "1 nT" for a field in T.
      f.read("scale", field.scale, *unit);
      if (f.has("full_scale")) {
        field.full_scale = 0.0;
        f.read("full_scale", *field.full_scale, *unit);
      }
    }
  } else {
    for (const char* key : {"scale", "full_scale"}) {
      if (f.has(key)) f.problem(key, "only with to: a field that is not published has no unit to scale to");
    }
    f.leave({"scale", "full_scale"});
  }
  f.finish();
  return field;
}

/// The frame under `key` of `r` (frame: or command:), its fields carrying `topic`'s.
void readFrame(bus::ParamReader& r, const std::string& key, const std::string& topic, const FieldUnitLookup& unit_of,
               FrameSpec& frame) {
  auto f = r.section(key);
  f.read("name", frame.name);
  std::string sync;
  f.read("sync", sync);
  if (const auto bytes = hexBytes(sync)) {
    frame.sync = *bytes;
  } else {
    f.problem("sync", "'" + sync + "' is not bytes in hex, two digits each (\"AA 55\")");
  }
  bool little_endian = true;
  readByteOrder(f, little_endian);
  auto field_readers = f.list("fields");
  for (auto& field : field_readers) frame.fields.push_back(readField(field, topic, little_endian, unit_of));
  auto c = f.section("checksum");
  readChecksum(c, frame);
  c.finish();
  for (const SpecProblem& p : frame.validate()) {
    if (p.field >= 0) {
      field_readers[static_cast<std::size_t>(p.field)].problem(p.key, p.reason);
    } else if (p.key == "checksum") {
      c.problem("", p.reason);
    } else {
      f.problem(p.key, p.reason);
    }
  }
  f.finish();
}

}  // namespace

std::vector<std::string> LineSettings::validate() const {
  static const std::set<std::uint32_t> kRates = {1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600};
  std::vector<std::string> errors;
  if (!kRates.count(baud)) errors.push_back("baud: " + std::to_string(baud) + " is not a standard rate (1200 .. 921600)");
  // A binary frame's bytes need all 8 bits: with fewer the UART drops the top one.
  if (data_bits != 8) errors.push_back("data_bits: " + std::to_string(data_bits) + " must be 8 for binary frames");
  if (parity != "none" && parity != "even" && parity != "odd") errors.push_back("parity: '" + parity + "' is not none, even or odd");
  if (stop_bits != 1 && stop_bits != 2) errors.push_back("stop_bits: " + std::to_string(stop_bits) + " is neither 1 nor 2");
  return errors;
}

std::string findDeviceDescription(const std::string& scenario_file, const std::string& name) {
  return bus::findBesideOrIn(scenario_file, name, bus::deviceDirs());
}

DeviceProtocol readDeviceProtocol(const std::string& path, const FieldUnitLookup& unit_of, bus::ConfigProblems& problems) {
  DeviceProtocol protocol;
  protocol.file = path;
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    problems.add(path + ": cannot read the device description: " + e.what());
    return protocol;
  }
  bus::ParamReader r(root, path, "", problems);
  r.read("name", protocol.name);
  r.read("topic", protocol.topic);
  if (protocol.topic.empty()) r.problem("topic", "the bus topic its frames carry is required");
  r.read("sensor_axes", protocol.sensor_axes);
  auto line = r.section("line");
  line.read("baud", protocol.line.baud);
  line.read("data_bits", protocol.line.data_bits);
  line.read("parity", protocol.line.parity);
  line.read("stop_bits", protocol.line.stop_bits);
  line.problems(protocol.line.validate());
  line.finish();

  readFrame(r, "frame", protocol.topic, unit_of, protocol.frame);
  r.read("command_topic", protocol.command_topic);
  if (r.has("command")) {
    if (protocol.command_topic.empty()) r.problem("command", "a command frame needs command_topic: the bus topic it carries");
    protocol.command.emplace();
    readFrame(r, "command", protocol.command_topic, unit_of, *protocol.command);
  } else if (!protocol.command_topic.empty()) {
    r.problem("command_topic", "an actuator's command topic needs its command: frame");
  }
  std::string reply = "periodic";
  r.read("reply", reply);
  if (reply == "per_command") {
    protocol.reply = ReplyMode::kPerCommand;
    if (!protocol.command) r.problem("reply", "per_command answers command frames: the description has no command:");
  } else if (reply != "periodic") {
    r.problem("reply", "'" + reply + "' is neither periodic nor per_command");
  }
  if (r.has("rate_hz")) {
    protocol.rate_hz = 0.0;
    r.read("rate_hz", *protocol.rate_hz, "Hz");
    if (!(*protocol.rate_hz > 0.0 && *protocol.rate_hz <= 10000.0)) r.problem("rate_hz", "must be in (0, 10 kHz]");
    if (protocol.reply == ReplyMode::kPerCommand) {
      r.problem("rate_hz", "a device that answers each command (reply: per_command) sends at its commands' rate");
    }
  }
  r.finish();
  return protocol;
}

}  // namespace flatsat::device_protocol
