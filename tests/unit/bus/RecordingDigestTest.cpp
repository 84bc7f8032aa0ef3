// SPDX-License-Identifier: Apache-2.0
// The recording digest against its definition (bus/RecordingDigest.hpp),
// hashed here from the rows with OpenSSL's one-shot SHA-256, not through
// the project's stream digests.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <tuple>
#include <unistd.h>

#include <openssl/evp.h>

#include "bus/Recording.hpp"
#include "bus/RecordingMeta.hpp"
#include "bus/Serialization.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"

using flatsat::bus::Recording;

namespace {

using Row = std::tuple<std::string, std::string, std::uint64_t, std::vector<std::uint8_t>>;  // topic, source, step, payload

std::string sha256(const std::string& bytes) {
  unsigned char hash[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_Digest(bytes.data(), bytes.size(), hash, &length, EVP_sha256(), nullptr);
  return {reinterpret_cast<const char*>(hash), length};
}

std::string littleEndian(std::uint64_t value) {
  std::string bytes(8, '\0');
  for (int i = 0; i < 8; ++i) bytes[i] = static_cast<char>(value >> (8 * i));
  return bytes;
}

/// The definition, spelled out: streams by (topic, source), rows by (step, payload).
std::string expectedDigest(std::vector<Row> rows) {
  std::sort(rows.begin(), rows.end());
  std::map<std::pair<std::string, std::string>, std::pair<std::string, std::uint64_t>> streams;
  for (const auto& [topic, source, step, payload] : rows) {
    auto& [bytes, count] = streams[{topic, source}];
    bytes += littleEndian(step) + littleEndian(payload.size()) + std::string(payload.begin(), payload.end());
    ++count;
  }
  std::string all;
  for (const auto& [key, stream] : streams) {
    all += key.first + '\0' + key.second + '\0' + littleEndian(stream.second) + sha256(stream.first);
  }
  std::string hex;
  for (unsigned char c : sha256(all)) {
    static const char* kHex = "0123456789abcdef";
    hex += kHex[c >> 4];
    hex += kHex[c & 15];
  }
  return hex;
}

std::vector<std::uint8_t> faultEvent(const std::string& kind) {
  using Def = std::remove_cvref_t<decltype(flatsat::bus::topics::kFaultEvent)>;
  Def::Type event;
  flatsat::bus::setText(event.kind(), kind);
  return flatsat::bus::serialize<Def>(event);
}

struct TempRecording {
  std::filesystem::path path = std::filesystem::temp_directory_path() /
                               ("flatsat-digest-" + std::to_string(::getpid()) + ".sqlite");
  TempRecording() { remove(); }
  ~TempRecording() { remove(); }
  void remove() const {
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path.string() + suffix);
  }
};

void insert(Recording& r, const Row& row) {
  r.insert(std::get<0>(row), std::get<2>(row), std::get<1>(row), 0, std::get<3>(row));
}

}  // namespace

TEST_CASE("a recording's digest is its definition's, as stored and as read back, whatever the arrival order",
          "[bus][recording][digest]") {
  const std::vector<Row> rows = {
      {"flatsat/truth", "dynamics_server", 0, {1, 2, 3}}, {"flatsat/gyro", "gyro", 0, {4}},
      {"flatsat/truth", "dynamics_server", 1, {5, 6}},    {"flatsat/gyro", "gyro_bridge", 1, {7}},
      {"flatsat/gyro", "gyro", 2, {}},                    {"flatsat/truth", "dynamics_server", 2, {8}},
  };
  const std::string expected = expectedDigest(rows);
  TempRecording file;
  {
    Recording writer(file.path.string(), Recording::Access::kCreate);
    for (const Row& row : rows) insert(writer, row);
    // Left out: health and a wall-clock verdict; kept: a fault the scenario injected.
    writer.insert(std::string(flatsat::bus::topics::kHealth.name), 7, "gyro", 0, {9, 9});
    writer.insert(std::string(flatsat::bus::topics::kFaultEvent.name), 1, "dynamics_server", 0, faultEvent("late"));
    writer.commit();
    REQUIRE(writer.storedDigest() == expected);
    CHECK(writer.digest() == expected);
    writer.insert(std::string(flatsat::bus::topics::kFaultEvent.name), 2, "fault_injector", 0, faultEvent("bias"));
  }
  std::vector<Row> with_fault = rows;
  with_fault.emplace_back(std::string(flatsat::bus::topics::kFaultEvent.name), "fault_injector", 2, faultEvent("bias"));
  const Recording reader(file.path.string(), Recording::Access::kRead);
  CHECK(reader.digest() == expectedDigest(with_fault));
  CHECK(reader.meta(flatsat::bus::meta::kDigest) == expectedDigest(with_fault));
  CHECK(expectedDigest(with_fault) != expected);
}

TEST_CASE("a stream stored out of step order, or a step stored twice, is read back in order and kept by no writer",
          "[bus][recording][digest]") {
  const std::vector<Row> rows = {
      {"t", "a", 3, {3}}, {"t", "b", 0, {0}}, {"t", "a", 1, {1}}, {"t", "a", 2, {2}}, {"t", "a", 2, {1}}, {"t", "b", 1, {1}},
  };
  TempRecording file;
  {
    Recording writer(file.path.string(), Recording::Access::kCreate);
    for (const Row& row : rows) insert(writer, row);
    writer.commit();
    CHECK_FALSE(writer.storedDigest().has_value());
  }
  const Recording reader(file.path.string(), Recording::Access::kRead);
  CHECK(reader.digest() == expectedDigest(rows));
  CHECK(reader.meta(flatsat::bus::meta::kDigest).empty());
}

TEST_CASE("a writer of a recording that held samples keeps no digest, nor one that erased some",
          "[bus][recording][digest]") {
  TempRecording file;
  {
    Recording first(file.path.string(), Recording::Access::kCreate);
    insert(first, {"t", "a", 0, {0}});
    insert(first, {"t", "a", 1, {1}});
  }
  REQUIRE_FALSE(Recording(file.path.string(), Recording::Access::kRead).meta(flatsat::bus::meta::kDigest).empty());
  {
    Recording resumed(file.path.string(), Recording::Access::kCreate);  // as a resumed run's recorder
    insert(resumed, {"t", "a", 2, {2}});
    CHECK_FALSE(resumed.storedDigest().has_value());
  }
  CHECK(Recording(file.path.string(), Recording::Access::kRead).meta(flatsat::bus::meta::kDigest).empty());
  CHECK(Recording(file.path.string(), Recording::Access::kRead).digest() ==
        expectedDigest({{"t", "a", 0, {0}}, {"t", "a", 1, {1}}, {"t", "a", 2, {2}}}));
  file.remove();
  {
    Recording writer(file.path.string(), Recording::Access::kCreate);
    insert(writer, {"t", "a", 0, {0}});
    insert(writer, {"t", "a", 1, {1}});
    writer.eraseAfter(0);
    CHECK_FALSE(writer.storedDigest().has_value());
  }
}
