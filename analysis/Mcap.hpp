// SPDX-License-Identifier: Apache-2.0
#pragma once
// MCAP, the container rosbag2 and Foxglove record in: a writer of indexed,
// zstd-chunked files and a reader of their summary section. Record layouts,
// CRCs and offsets as the MCAP Format Specification (major version 0,
// mcap.dev/spec) gives them; the test tier tests/interop reads what this
// writes with @mcap/core.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace flatsat::analysis {

/// CRC-32 (ISO-HDLC: reflected 0x04C11DB7, init and xorout 0xFFFFFFFF), the
/// checksum MCAP uses throughout; `crc` carries a running value across calls.
std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0);

using McapMap = std::map<std::string, std::string>;

/// Writes an MCAP file: Header; Schema and Channel records, then Messages,
/// in zstd Chunks of about `chunk_bytes`, each followed by its Message Index
/// records; Metadata; DataEnd with the data section's CRC; a summary section
/// (Schemas, Channels, Statistics, Metadata Index, Chunk Index, grouped by
/// opcode) with its Summary Offset records; Footer with the summary's CRC.
class McapWriter {
 public:
  /// @throws std::runtime_error naming `path` when it cannot be written.
  McapWriter(const std::string& path, const std::string& library, std::size_t chunk_bytes = 1 << 20);
  /// Without close() the file is left unfinished (no footer), never made to look whole.
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  std::uint16_t addSchema(const std::string& name, const std::string& encoding, const std::string& data);
  std::uint16_t addChannel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                           const McapMap& metadata = {});
  /// One message; `log_time_ns` also orders the chunk's index. Sequence numbers count per channel.
  void addMessage(std::uint16_t channel_id, std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
                  const std::uint8_t* data, std::size_t size);
  void addMetadata(const std::string& name, const McapMap& metadata);
  /// Writes the rest of the file; @throws std::runtime_error when the file could not be written.
  void close();

 private:
  struct ChunkIndex {
    std::uint64_t start = 0, end = 0, offset = 0, length = 0;
    std::map<std::uint16_t, std::uint64_t> index_offsets;
    std::uint64_t index_length = 0, compressed = 0, uncompressed = 0;
  };
  void writeData(const std::vector<std::uint8_t>& bytes);  // to the file, counted in the data section's CRC
  void flushChunk();

  std::ofstream out_;
  std::string path_;
  std::size_t chunk_bytes_;
  std::uint64_t offset_ = 0;
  std::uint32_t data_crc_ = 0;
  bool closed_ = false;
  std::vector<std::vector<std::uint8_t>> schemas_, channels_;  // their records, for the summary
  std::vector<std::uint8_t> chunk_;                             // uncompressed records of the open chunk
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::vector<ChunkIndex> chunks_;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> metadata_at_;  // offset, length
  std::vector<std::string> metadata_names_;
  std::map<std::uint16_t, std::uint64_t> counts_;
  std::map<std::uint16_t, std::uint32_t> sequence_;
  std::uint64_t messages_ = 0, first_ = UINT64_MAX, last_ = 0;
};

/// An MCAP file's summary section as a reader finds it from the footer.
struct McapSummary {
  struct Channel {
    std::uint16_t id = 0;
    std::string topic, message_encoding, schema_name, schema_encoding;
    McapMap metadata;
    std::uint64_t messages = 0;
  };
  std::vector<Channel> channels;  // by id
  std::uint64_t messages = 0, first_ns = 0, last_ns = 0;
  std::uint32_t chunks = 0;
  std::map<std::string, McapMap> metadata;  // by record name
};

/// Reads the summary (checking the magic, the footer's summary CRC and the
/// records' lengths) and the Metadata records it indexes.
/// @throws std::runtime_error naming the file and what is wrong.
McapSummary readMcapSummary(const std::string& path);

}  // namespace flatsat::analysis
