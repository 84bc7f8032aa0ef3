// SPDX-License-Identifier: Apache-2.0
#pragma once
// What a recording holds, as `ros2 bag info` tells of a bag: `flatsat info`.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace flatsat::analysis {

struct RecordedTopic {
  std::string name;                 // "flatsat/truth"
  std::string type;                 // its IDL type, "flatsat::msg::TruthState"; "" : not a registry topic
  std::set<std::string> sources;    // who published what was recorded
  std::uint64_t samples = 0;
  double rate_hz = 0.0;             // [Hz] samples over the run's simulated span (0: one instant)
};

struct RecordingInfo {
  std::string path;
  std::uint64_t size_bytes = 0;     // the file with its write-ahead log
  std::string scenario;             // the scenario's name
  std::string mode;                 // lockstep | paced
  std::string digest;               // recording_sha256, as summary.json gives it, computed from the samples
  std::string recorded_digest;      // the one its recorder kept as it stored them ("": none, as after a crash)
  /// The samples are not those the recorder stored: changed or added since.
  bool changedSinceRecorded() const { return !recorded_digest.empty() && recorded_digest != digest; }
  std::uint64_t first_step = 0, last_step = 0;
  double sim_duration_s = 0.0;      // [s] first to last stamp of any sample
  double wall_duration_s = 0.0;     // [s] first to last health sample's wall clock (0: none recorded)
  std::uint64_t samples = 0;
  std::vector<RecordedTopic> topics;  // by name
};

/// Reads `path` (a recording.sqlite). @throws std::runtime_error naming the file and the reason.
RecordingInfo describeRecording(const std::string& path);

nlohmann::ordered_json toJson(const RecordingInfo& info);
/// The table `flatsat info` prints: a header of the run, then a line per topic.
std::string infoTable(const RecordingInfo& info);

}  // namespace flatsat::analysis
