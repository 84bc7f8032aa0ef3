// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace flatsat::bus {

/// Whether a recorded row stays out of a recording's digest: health (wall-
/// clock counts and times) and the fault events that are verdicts on the wall
/// clock rather than results of the simulation (kind late, lost, restarted or
/// intruder: a starved process, a kill, a foreign writer). A rig that was held
/// up or attacked and computed the same steps records the same digest.
bool outsideDigest(std::string_view topic, const std::uint8_t* payload, std::size_t size);

/// The digest a recording is known by (summary.json `recording_sha256`,
/// `flatsat info`): SHA-256 over its streams, one per (topic, source) in
/// byte order of topic then source, each given as topic, NUL, source, NUL,
/// its row count (8 bytes, little-endian) and the SHA-256 of its rows in
/// (step, payload) order, each row as its step and payload size (8 bytes
/// each, little-endian) and the payload. Rows outsideDigest() are not in it.
///
/// Hashed stream by stream, the rows can go in as they are stored: a
/// producer's samples arrive in step order, so the recorder's digest is done
/// when its recording is (Recording keeps it in the meta table) and reading
/// the file back in storage order, without a sort, gives the same.
class StreamDigests {
 public:
  StreamDigests();
  ~StreamDigests();
  StreamDigests(StreamDigests&&) noexcept;
  StreamDigests& operator=(StreamDigests&&) noexcept;

  /// Adds a row in storage order. A row whose step is not after its stream's
  /// last marks the stream unordered (out of order, or a step stored twice):
  /// its rows must then be given again in order (restartStream()).
  void add(std::string_view topic, std::string_view source, std::uint64_t step, const std::uint8_t* payload,
           std::size_t size);
  /// Adds a row that is known to come in (step, payload) order.
  void addOrdered(std::string_view topic, std::string_view source, std::uint64_t step,
                  const std::uint8_t* payload, std::size_t size);
  /// The streams marked unordered, as (topic, source).
  std::vector<std::pair<std::string, std::string>> unordered() const;
  /// Forgets what one stream was given, for its rows to be added again in order.
  void restartStream(const std::string& topic, const std::string& source);
  /// The digest of what was added so far, hex; rows may be added after. No stream may be unordered.
  std::string hex() const;

 private:
  struct Stream;
  Stream& stream(std::string_view topic, std::string_view source);
  /// topic -> source -> stream; std::less<>: found without a copy of the names.
  std::map<std::string, std::map<std::string, std::unique_ptr<Stream>, std::less<>>, std::less<>> streams_;
};

}  // namespace flatsat::bus
