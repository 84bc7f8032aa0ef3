// SPDX-License-Identifier: Apache-2.0
// The MCAP writer against the specification's fixed points (magic, CRC-32
// check value, footer layout) and its own summary reader; tests/interop reads
// the same files with @mcap/core.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "analysis/Mcap.hpp"
#include "analysis/McapSchemas.hpp"

namespace fs = std::filesystem;
using namespace flatsat::analysis;

namespace {

std::vector<std::uint8_t> fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::uint64_t u64At(const std::vector<std::uint8_t>& b, std::size_t at) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | b[at + static_cast<std::size_t>(i)];
  return v;
}

std::string scratchMcap(const std::string& tag) {
  return (fs::temp_directory_path() / ("flatsat-mcap-" + tag + "-" + std::to_string(::getpid()) + ".mcap")).string();
}

}  // namespace

TEST_CASE("MCAP's CRC-32 is the ISO-HDLC CRC: its check value", "[analysis]") {
  const std::string check = "123456789";
  CHECK(crc32(reinterpret_cast<const std::uint8_t*>(check.data()), check.size()) == 0xCBF43926u);
  // A running CRC over two pieces is the CRC of the whole.
  const auto* p = reinterpret_cast<const std::uint8_t*>(check.data());
  CHECK(crc32(p + 4, 5, crc32(p, 4)) == 0xCBF43926u);
}

TEST_CASE("an MCAP file: magic at both ends, a footer pointing at its summary, counts and metadata read back",
          "[analysis]") {
  const std::string path = scratchMcap("basic");
  {
    McapWriter writer(path, "flatsat test", 64);  // small chunks: several of them
    const auto schema = writer.addSchema("pkg::Point", "omgidl", "module pkg { struct Point { double x; }; };");
    const auto a = writer.addChannel(schema, "points", "cdr", {{"sources", "gyro"}});
    const auto b = writer.addChannel(schema, "other", "cdr");
    const std::uint8_t payload[12] = {0, 1, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8};
    for (std::uint64_t t = 0; t < 10; ++t) writer.addMessage(a, 1000 + t, 1000 + t, payload, sizeof payload);
    writer.addMessage(b, 5000, 5000, payload, 4);
    writer.addMetadata("flatsat", {{"scenario", "default"}, {"recording_sha256", "ab"}});
    writer.close();
  }
  const auto bytes = fileBytes(path);
  const std::string magic("\x89MCAP0\r\n", 8);
  REQUIRE(bytes.size() > 100);
  CHECK(std::string(bytes.begin(), bytes.begin() + 8) == magic);
  CHECK(std::string(bytes.end() - 8, bytes.end()) == magic);
  // Footer: opcode 0x02, content length 20, then summary_start, summary_offset_start, summary_crc.
  const std::size_t footer = bytes.size() - 8 - 29;
  CHECK(bytes[footer] == 0x02);
  CHECK(u64At(bytes, footer + 1) == 20);
  const auto summary_start = u64At(bytes, footer + 9);
  CHECK(summary_start > 8);
  CHECK(summary_start < footer);
  // The record before the summary is DataEnd (0x0F, 4 bytes), whose CRC covers every byte before it.
  const std::size_t data_end = summary_start - 13;
  CHECK(bytes[data_end] == 0x0F);
  std::uint32_t stored = 0;
  std::memcpy(&stored, &bytes[data_end + 9], 4);
  CHECK(stored == crc32(bytes.data(), data_end));

  const auto summary = readMcapSummary(path);
  CHECK(summary.messages == 11);
  CHECK(summary.first_ns == 1000);
  CHECK(summary.last_ns == 5000);
  CHECK(summary.chunks > 1);
  REQUIRE(summary.channels.size() == 2);
  CHECK(summary.channels[0].topic == "points");
  CHECK(summary.channels[0].schema_name == "pkg::Point");
  CHECK(summary.channels[0].schema_encoding == "omgidl");
  CHECK(summary.channels[0].messages == 10);
  CHECK(summary.channels[0].metadata.at("sources") == "gyro");
  CHECK(summary.channels[1].messages == 1);
  CHECK(summary.metadata.at("flatsat").at("recording_sha256") == "ab");

  // One byte changed in the summary: its CRC no longer holds, and the reader says so.
  auto damaged = bytes;
  damaged[summary_start + 20] ^= 0xFF;
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(damaged.data()),
                                               static_cast<std::streamsize>(damaged.size()));
  CHECK_THROWS_WITH(readMcapSummary(path), Catch::Contains("CRC does not match"));
  // A footer whose summary offset start points past it (and no CRC to catch
  // that): refused, not read out of bounds.
  auto pointing_out = bytes;
  const std::uint64_t beyond = footer + 100;
  std::memcpy(&pointing_out[footer + 17], &beyond, 8);
  std::memset(&pointing_out[footer + 25], 0, 4);
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(pointing_out.data()),
                                               static_cast<std::streamsize>(pointing_out.size()));
  CHECK_THROWS_WITH(readMcapSummary(path), Catch::Contains("lies outside the summary section"));
  std::ofstream(path, std::ios::binary) << "not an mcap file at all, but long enough to have a footer";
  CHECK_THROWS_WITH(readMcapSummary(path), Catch::Contains("not an MCAP file"));
  fs::remove(path);
}

TEST_CASE("an MCAP writer never closed leaves a file that no reader takes for whole", "[analysis]") {
  const std::string path = scratchMcap("unclosed");
  {
    McapWriter writer(path, "flatsat test");
    const auto channel = writer.addChannel(writer.addSchema("pkg::Point", "omgidl", "module pkg {};"), "points", "cdr");
    const std::uint8_t payload[4] = {0, 1, 0, 0};
    writer.addMessage(channel, 1, 1, payload, sizeof payload);
  }  // as when an export throws part-way
  CHECK_THROWS_WITH(readMcapSummary(path), Catch::Contains("not an MCAP file"));
  fs::remove(path);
}

TEST_CASE("the omgidl schemas are self-contained IDL: the header type inlined, no directives", "[analysis]") {
  const std::string truth(omgIdlSchema("flatsat::msg::TruthState"));
  CHECK(truth.find("struct TruthState") != std::string::npos);
  CHECK(truth.find("struct SampleHeader") != std::string::npos);  // from Common.idl
  CHECK(truth.find("#include") == std::string::npos);
  CHECK(truth.find("struct SampleHeader") == truth.rfind("struct SampleHeader"));
  CHECK(omgIdlSchema("flatsat::msg::NoSuchType").empty());
  CHECK(foxgloveJsonSchema("foxglove.FrameTransform").find("\"child_frame_id\"") != std::string::npos);
  CHECK(foxgloveJsonSchema("foxglove.Log").find("\"level\"") != std::string::npos);
}
