// SPDX-License-Identifier: Apache-2.0
#include "analysis/Mcap.hpp"

#include <zstd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <tuple>

namespace flatsat::analysis {

namespace {

// Opcodes (MCAP spec, "Records").
constexpr std::uint8_t kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05,
                       kChunk = 0x06, kMessageIndex = 0x07, kChunkIndex = 0x08, kStatistics = 0x0B,
                       kMetadata = 0x0C, kMetadataIndex = 0x0D, kSummaryOffset = 0x0E, kDataEnd = 0x0F;
constexpr std::array<std::uint8_t, 8> kMagic{0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};
// zstd's fastest level: a day's recording is exported in seconds, and still shrinks about fivefold.
constexpr int kZstdLevel = 1;

/// Little-endian fields and MCAP's length-prefixed strings, maps and arrays.
struct Bytes {
  std::vector<std::uint8_t> b;
  template <class T>
  void le(T v) {
    for (std::size_t i = 0; i < sizeof(T); ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void raw(const void* data, std::size_t size) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    b.insert(b.end(), p, p + size);
  }
  void str(const std::string& s) {
    le<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    raw(s.data(), s.size());
  }
  void map(const McapMap& m) {
    Bytes entries;
    for (const auto& [k, v] : m) {
      entries.str(k);
      entries.str(v);
    }
    le<std::uint32_t>(static_cast<std::uint32_t>(entries.b.size()));
    raw(entries.b.data(), entries.b.size());
  }
  void countMap(const std::map<std::uint16_t, std::uint64_t>& m) {
    le<std::uint32_t>(static_cast<std::uint32_t>(m.size() * 10));
    for (const auto& [k, v] : m) {
      le(k);
      le(v);
    }
  }
};

std::vector<std::uint8_t> record(std::uint8_t opcode, const Bytes& content) {
  Bytes r;
  r.le(opcode);
  r.le<std::uint64_t>(content.b.size());
  r.raw(content.b.data(), content.b.size());
  return std::move(r.b);
}

const std::array<std::uint32_t, 256>& crcTable() {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  return table;
}

}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc) {
  const auto& table = crcTable();
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) crc = table[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
  return ~crc;
}

McapWriter::McapWriter(const std::string& path, const std::string& library, std::size_t chunk_bytes)
    : out_(path, std::ios::binary | std::ios::trunc), path_(path), chunk_bytes_(chunk_bytes) {
  if (!out_) throw std::runtime_error(path + ": cannot write");
  writeData({kMagic.begin(), kMagic.end()});
  Bytes header;
  header.str("");  // no well-known profile: the channels say their encodings
  header.str(library);
  writeData(record(kHeader, header));
}

// Not closed means the writing failed part-way: the file is left without
// its summary and footer, which every reader refuses, rather than made to
// look whole.
McapWriter::~McapWriter() = default;

void McapWriter::writeData(const std::vector<std::uint8_t>& bytes) {
  data_crc_ = crc32(bytes.data(), bytes.size(), data_crc_);
  out_.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  offset_ += bytes.size();
}

std::uint16_t McapWriter::addSchema(const std::string& name, const std::string& encoding, const std::string& data) {
  const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);  // 0 means "no schema"
  Bytes s;
  s.le(id);
  s.str(name);
  s.str(encoding);
  s.str(data);  // uint32 length-prefixed bytes
  schemas_.push_back(record(kSchema, s));
  writeData(schemas_.back());
  return id;
}

std::uint16_t McapWriter::addChannel(std::uint16_t schema_id, const std::string& topic,
                                     const std::string& message_encoding, const McapMap& metadata) {
  const auto id = static_cast<std::uint16_t>(channels_.size() + 1);
  Bytes c;
  c.le(id);
  c.le(schema_id);
  c.str(topic);
  c.str(message_encoding);
  c.map(metadata);
  channels_.push_back(record(kChannel, c));
  writeData(channels_.back());
  counts_[id] = 0;
  return id;
}

void McapWriter::addMessage(std::uint16_t channel_id, std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
                            const std::uint8_t* data, std::size_t size) {
  Bytes m;
  m.le(channel_id);
  m.le(sequence_[channel_id]++);
  m.le(log_time_ns);
  m.le(publish_time_ns);
  m.raw(data, size);
  if (chunk_.empty()) chunk_start_ = chunk_end_ = log_time_ns;
  chunk_index_[channel_id].emplace_back(log_time_ns, chunk_.size());
  const auto r = record(kMessage, m);
  chunk_.insert(chunk_.end(), r.begin(), r.end());
  chunk_start_ = std::min(chunk_start_, log_time_ns);
  chunk_end_ = std::max(chunk_end_, log_time_ns);
  first_ = std::min(first_, log_time_ns);
  last_ = std::max(last_, log_time_ns);
  ++counts_[channel_id];
  ++messages_;
  if (chunk_.size() >= chunk_bytes_) flushChunk();
}

void McapWriter::flushChunk() {
  if (chunk_.empty()) return;
  std::vector<std::uint8_t> compressed(ZSTD_compressBound(chunk_.size()));
  const std::size_t n = ZSTD_compress(compressed.data(), compressed.size(), chunk_.data(), chunk_.size(), kZstdLevel);
  if (ZSTD_isError(n)) throw std::runtime_error(path_ + ": zstd: " + ZSTD_getErrorName(n));
  ChunkIndex index;
  index.start = chunk_start_;
  index.end = chunk_end_;
  index.offset = offset_;
  index.compressed = n;
  index.uncompressed = chunk_.size();
  Bytes c;
  c.le(chunk_start_);
  c.le(chunk_end_);
  c.le<std::uint64_t>(chunk_.size());
  c.le(crc32(chunk_.data(), chunk_.size()));
  c.str("zstd");
  c.le<std::uint64_t>(n);
  c.raw(compressed.data(), n);
  const auto chunk_record = record(kChunk, c);
  index.length = chunk_record.size();
  writeData(chunk_record);
  const std::uint64_t indexes_start = offset_;
  for (const auto& [channel, entries] : chunk_index_) {
    Bytes mi;
    mi.le(channel);
    mi.le<std::uint32_t>(static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [time, at] : entries) {
      mi.le(time);
      mi.le(at);
    }
    index.index_offsets[channel] = offset_;
    writeData(record(kMessageIndex, mi));
  }
  index.index_length = offset_ - indexes_start;
  chunks_.push_back(index);
  chunk_.clear();
  chunk_index_.clear();
}

void McapWriter::addMetadata(const std::string& name, const McapMap& metadata) {
  Bytes m;
  m.str(name);
  m.map(metadata);
  const auto r = record(kMetadata, m);
  metadata_at_.emplace_back(offset_, r.size());
  metadata_names_.push_back(name);
  writeData(r);
}

void McapWriter::close() {
  if (closed_) return;
  closed_ = true;
  flushChunk();
  Bytes end;
  end.le(data_crc_);  // every byte from the file's start up to this record
  writeData(record(kDataEnd, end));

  // The summary section, grouped by opcode, each group located by a Summary Offset.
  const std::uint64_t summary_start = offset_;
  std::vector<std::uint8_t> summary;
  std::vector<std::tuple<std::uint8_t, std::uint64_t, std::uint64_t>> groups;
  auto group = [&](std::uint8_t opcode, const std::vector<std::vector<std::uint8_t>>& records) {
    if (records.empty()) return;
    const std::uint64_t start = summary_start + summary.size();
    for (const auto& r : records) summary.insert(summary.end(), r.begin(), r.end());
    groups.emplace_back(opcode, start, summary_start + summary.size() - start);
  };
  group(kSchema, schemas_);
  group(kChannel, channels_);
  Bytes stats;
  stats.le(messages_);
  stats.le(static_cast<std::uint16_t>(schemas_.size()));
  stats.le(static_cast<std::uint32_t>(channels_.size()));
  stats.le<std::uint32_t>(0);  // attachments
  stats.le(static_cast<std::uint32_t>(metadata_at_.size()));
  stats.le(static_cast<std::uint32_t>(chunks_.size()));
  stats.le(messages_ ? first_ : 0);
  stats.le(messages_ ? last_ : 0);
  stats.countMap(counts_);
  group(kStatistics, {record(kStatistics, stats)});
  std::vector<std::vector<std::uint8_t>> metadata_index;
  for (std::size_t i = 0; i < metadata_at_.size(); ++i) {
    Bytes mi;
    mi.le(metadata_at_[i].first);
    mi.le(metadata_at_[i].second);
    mi.str(metadata_names_[i]);
    metadata_index.push_back(record(kMetadataIndex, mi));
  }
  group(kMetadataIndex, metadata_index);
  std::vector<std::vector<std::uint8_t>> chunk_index;
  for (const auto& c : chunks_) {
    Bytes ci;
    ci.le(c.start);
    ci.le(c.end);
    ci.le(c.offset);
    ci.le(c.length);
    ci.countMap(c.index_offsets);
    ci.le(c.index_length);
    ci.str("zstd");
    ci.le(c.compressed);
    ci.le(c.uncompressed);
    chunk_index.push_back(record(kChunkIndex, ci));
  }
  group(kChunkIndex, chunk_index);
  const std::uint64_t summary_offset_start = summary_start + summary.size();
  for (const auto& [opcode, start, length] : groups) {
    Bytes so;
    so.le(opcode);
    so.le(start);
    so.le(length);
    const auto r = record(kSummaryOffset, so);
    summary.insert(summary.end(), r.begin(), r.end());
  }
  Bytes footer;
  footer.le(kFooter);
  footer.le<std::uint64_t>(20);
  footer.le(summary_start);
  footer.le(summary_offset_start);
  summary.insert(summary.end(), footer.b.begin(), footer.b.end());
  // The summary CRC runs from the summary's start through summary_offset_start.
  Bytes crc;
  crc.le(crc32(summary.data(), summary.size()));
  summary.insert(summary.end(), crc.b.begin(), crc.b.end());
  summary.insert(summary.end(), kMagic.begin(), kMagic.end());
  out_.write(reinterpret_cast<const char*>(summary.data()), static_cast<std::streamsize>(summary.size()));
  out_.close();
  if (!out_) throw std::runtime_error(path_ + ": cannot write");
}

namespace {

/// Reads little-endian fields from a record's bytes, refusing to run past them.
struct Reader {
  const std::uint8_t* p;
  std::size_t size, at = 0;
  std::string where;
  void need(std::size_t n) const {
    if (at + n > size) throw std::runtime_error(where + ": a record ends before its fields do");
  }
  template <class T>
  T le() {
    need(sizeof(T));
    T v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) v |= static_cast<T>(static_cast<T>(p[at + i]) << (8 * i));
    at += sizeof(T);
    return v;
  }
  std::string str() {
    const auto n = le<std::uint32_t>();
    need(n);
    std::string s(reinterpret_cast<const char*>(p + at), n);
    at += n;
    return s;
  }
  McapMap map() {
    const auto n = le<std::uint32_t>();
    need(n);
    const std::size_t end = at + n;
    McapMap m;
    while (at < end) {
      auto k = str();
      m[k] = str();
    }
    return m;
  }
};

std::vector<std::uint8_t> readAt(std::ifstream& in, std::uint64_t offset, std::uint64_t size, const std::string& path) {
  std::vector<std::uint8_t> bytes(size);
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (!in) throw std::runtime_error(path + ": ends before offset " + std::to_string(offset + size));
  return bytes;
}

}  // namespace

McapSummary readMcapSummary(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw std::runtime_error(path + ": cannot read");
  const auto size = static_cast<std::uint64_t>(in.tellg());
  constexpr std::uint64_t kFooterRecord = 1 + 8 + 20;
  if (size < 2 * kMagic.size() + kFooterRecord) throw std::runtime_error(path + ": too short for an MCAP file");
  const auto head = readAt(in, 0, kMagic.size(), path);
  const auto tail = readAt(in, size - kFooterRecord - kMagic.size(), kFooterRecord + kMagic.size(), path);
  if (!std::equal(kMagic.begin(), kMagic.end(), head.begin()) ||
      !std::equal(kMagic.begin(), kMagic.end(), tail.end() - 8)) {
    throw std::runtime_error(path + ": not an MCAP file (no magic at its start and end)");
  }
  Reader footer{tail.data(), kFooterRecord, 0, path + ": footer"};
  if (footer.le<std::uint8_t>() != kFooter || footer.le<std::uint64_t>() != 20) {
    throw std::runtime_error(path + ": no footer record before the closing magic");
  }
  const auto summary_start = footer.le<std::uint64_t>();
  const auto summary_offset_start = footer.le<std::uint64_t>();
  const auto summary_crc = footer.le<std::uint32_t>();
  const std::uint64_t footer_at = size - kFooterRecord - kMagic.size();
  if (summary_start == 0 || summary_start > footer_at) {
    throw std::runtime_error(path + ": no summary section (written without an index?)");
  }
  if (summary_offset_start != 0 && (summary_offset_start < summary_start || summary_offset_start > footer_at)) {
    throw std::runtime_error(path + ": the footer's summary offset start " + std::to_string(summary_offset_start) +
                             " lies outside the summary section [" + std::to_string(summary_start) + ", " +
                             std::to_string(footer_at) + "]");
  }
  const auto summary = readAt(in, summary_start, footer_at - summary_start, path);
  if (summary_crc != 0) {
    std::uint32_t crc = crc32(summary.data(), summary.size());
    crc = crc32(tail.data(), 1 + 8 + 16, crc);
    if (crc != summary_crc) throw std::runtime_error(path + ": the summary section's CRC does not match");
  }
  McapSummary out;
  std::map<std::uint16_t, std::pair<std::string, std::string>> schemas;
  std::map<std::uint16_t, std::uint64_t> counts;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> metadata_at;
  const std::uint64_t records_end = (summary_offset_start ? summary_offset_start : footer_at) - summary_start;
  for (std::size_t at = 0; at < records_end;) {
    Reader r{summary.data(), static_cast<std::size_t>(records_end), at, path + ": summary"};
    const auto opcode = r.le<std::uint8_t>();
    const auto length = r.le<std::uint64_t>();
    r.need(length);
    Reader c{summary.data() + r.at, static_cast<std::size_t>(length), 0, path + ": summary record"};
    if (opcode == kSchema) {
      const auto id = c.le<std::uint16_t>();
      auto name = c.str();
      schemas[id] = {name, c.str()};
    } else if (opcode == kChannel) {
      McapSummary::Channel ch;
      ch.id = c.le<std::uint16_t>();
      const auto schema = c.le<std::uint16_t>();
      ch.topic = c.str();
      ch.message_encoding = c.str();
      ch.metadata = c.map();
      if (schemas.count(schema)) std::tie(ch.schema_name, ch.schema_encoding) = schemas[schema];
      out.channels.push_back(ch);
    } else if (opcode == kStatistics) {
      out.messages = c.le<std::uint64_t>();
      c.le<std::uint16_t>();
      c.le<std::uint32_t>();
      c.le<std::uint32_t>();
      c.le<std::uint32_t>();
      out.chunks = c.le<std::uint32_t>();
      out.first_ns = c.le<std::uint64_t>();
      out.last_ns = c.le<std::uint64_t>();
      const auto bytes = c.le<std::uint32_t>();
      for (std::uint32_t i = 0; i < bytes / 10; ++i) {
        const auto id = c.le<std::uint16_t>();
        counts[id] = c.le<std::uint64_t>();
      }
    } else if (opcode == kMetadataIndex) {
      const auto offset = c.le<std::uint64_t>();
      metadata_at.emplace_back(offset, c.le<std::uint64_t>());
    }
    at = r.at + length;
  }
  for (auto& ch : out.channels) ch.messages = counts.count(ch.id) ? counts[ch.id] : 0;
  for (const auto& [offset, length] : metadata_at) {
    const auto bytes = readAt(in, offset, length, path);
    Reader r{bytes.data(), bytes.size(), 0, path + ": metadata"};
    if (r.le<std::uint8_t>() != kMetadata) throw std::runtime_error(path + ": a metadata index points elsewhere");
    r.le<std::uint64_t>();
    auto name = r.str();
    out.metadata[name] = r.map();
  }
  return out;
}

}  // namespace flatsat::analysis
