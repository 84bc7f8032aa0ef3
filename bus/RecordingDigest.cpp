// SPDX-License-Identifier: Apache-2.0
#include "bus/RecordingDigest.hpp"

#include <stdexcept>
#include <vector>

#include <openssl/evp.h>

#include "bus/Serialization.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"

namespace flatsat::bus {

namespace {

using Context = std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)>;

Context sha256() {
  Context ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("recording digest: OpenSSL has no SHA-256");
  }
  return ctx;
}

void addLittleEndian(EVP_MD_CTX* ctx, std::uint64_t value) {
  unsigned char bytes[8];
  for (int i = 0; i < 8; ++i) bytes[i] = static_cast<unsigned char>(value >> (8 * i));
  EVP_DigestUpdate(ctx, bytes, sizeof bytes);
}

}  // namespace

bool outsideDigest(std::string_view topic, const std::uint8_t* payload, std::size_t size) {
  if (topic == topics::kHealth.name) return true;
  if (topic != topics::kFaultEvent.name) return false;
  using EventDef = std::remove_cvref_t<decltype(topics::kFaultEvent)>;
  const std::string kind = text(deserialize<EventDef>(std::vector<std::uint8_t>(payload, payload + size)).kind());
  return kind == "late" || kind == "lost" || kind == "restarted" || kind == "intruder";
}

struct StreamDigests::Stream {
  Context rows = sha256();
  std::uint64_t count = 0;
  std::uint64_t last_step = 0;
  bool ordered = true;
};

StreamDigests::StreamDigests() = default;
StreamDigests::~StreamDigests() = default;
StreamDigests::StreamDigests(StreamDigests&&) noexcept = default;
StreamDigests& StreamDigests::operator=(StreamDigests&&) noexcept = default;

StreamDigests::Stream& StreamDigests::stream(std::string_view topic, std::string_view source) {
  auto by_topic = streams_.find(topic);
  if (by_topic == streams_.end()) by_topic = streams_.emplace(std::string(topic), decltype(by_topic->second){}).first;
  auto it = by_topic->second.find(source);
  if (it == by_topic->second.end()) it = by_topic->second.emplace(std::string(source), std::make_unique<Stream>()).first;
  return *it->second;
}

void StreamDigests::add(std::string_view topic, std::string_view source, std::uint64_t step,
                        const std::uint8_t* payload, std::size_t size) {
  Stream& s = stream(topic, source);
  if (!s.ordered) return;
  if (s.count > 0 && step <= s.last_step) {
    s.ordered = false;
    return;
  }
  addOrdered(topic, source, step, payload, size);
}

void StreamDigests::addOrdered(std::string_view topic, std::string_view source, std::uint64_t step,
                               const std::uint8_t* payload, std::size_t size) {
  Stream& s = stream(topic, source);
  addLittleEndian(s.rows.get(), step);
  addLittleEndian(s.rows.get(), size);
  EVP_DigestUpdate(s.rows.get(), payload, size);
  s.last_step = step;
  ++s.count;
}

std::vector<std::pair<std::string, std::string>> StreamDigests::unordered() const {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [topic, sources] : streams_) {
    for (const auto& [source, s] : sources) {
      if (!s->ordered) out.emplace_back(topic, source);
    }
  }
  return out;
}

void StreamDigests::restartStream(const std::string& topic, const std::string& source) {
  streams_[topic][source] = std::make_unique<Stream>();
}

std::string StreamDigests::hex() const {
  if (!unordered().empty()) throw std::logic_error("recording digest: a stream's rows were not given in order");
  const Context all = sha256();
  for (const auto& [topic, sources] : streams_) {  // std::string's order: byte order
    for (const auto& [source, s] : sources) {
      EVP_DigestUpdate(all.get(), topic.c_str(), topic.size() + 1);
      EVP_DigestUpdate(all.get(), source.c_str(), source.size() + 1);
      addLittleEndian(all.get(), s->count);
      const Context copy(EVP_MD_CTX_new(), EVP_MD_CTX_free);  // the stream goes on taking rows
      EVP_MD_CTX_copy_ex(copy.get(), s->rows.get());
      unsigned char rows[EVP_MAX_MD_SIZE];
      unsigned int length = 0;
      EVP_DigestFinal_ex(copy.get(), rows, &length);
      EVP_DigestUpdate(all.get(), rows, length);
    }
  }
  unsigned char hash[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_DigestFinal_ex(all.get(), hash, &length);
  static const char* kHex = "0123456789abcdef";
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) {
    hex += kHex[hash[i] >> 4];
    hex += kHex[hash[i] & 15];
  }
  return hex;
}

}  // namespace flatsat::bus
