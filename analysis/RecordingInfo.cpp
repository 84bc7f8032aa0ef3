// SPDX-License-Identifier: Apache-2.0
#include "analysis/RecordingInfo.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "bus/RecordingMeta.hpp"
#include "bus/Recording.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "msg/MsgJson.hpp"

namespace flatsat::analysis {
namespace {

std::uint64_t fileSize(const std::string& path) {
  std::uint64_t size = 0;
  std::error_code ignored;
  for (const std::string suffix : {"", "-wal"}) {
    if (std::filesystem::exists(path + suffix, ignored)) size += std::filesystem::file_size(path + suffix, ignored);
  }
  return size;
}

std::string typeOf(const std::string& topic) {
  std::string type;
  bus::forEachTopic([&](const auto& def) {
    if (def.name == topic) type = std::string(msg::idlName<typename std::remove_cvref_t<decltype(def)>::Type>());
  });
  return type;
}

/// The wall clock of the health samples stamped `step` (every node's own clock), the
/// earliest or the latest of them.
std::uint64_t healthWallNs(const bus::Recording& recording, std::uint64_t step, bool latest) {
  std::uint64_t chosen = latest ? 0 : std::numeric_limits<std::uint64_t>::max();
  recording.forEachAt(std::string(bus::topics::kHealth.name), step, [&](const std::string&, const auto& payload) {
    const auto wall = bus::deserialize<std::remove_cvref_t<decltype(bus::topics::kHealth)>>(payload).wall_time_ns();
    if (wall > 0) chosen = latest ? std::max(chosen, wall) : std::min(chosen, wall);
  });
  return chosen;
}

}  // namespace

RecordingInfo describeRecording(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error(path + ": no such recording");
  const bus::Recording recording(path, bus::Recording::Access::kRead);
  RecordingInfo info;
  info.path = path;
  info.size_bytes = fileSize(path);
  info.scenario = recording.meta("scenario");
  info.mode = recording.meta("mode");
  info.digest = recording.digest();
  info.recorded_digest = recording.meta(bus::meta::kDigest);
  const auto extents = recording.extents();
  if (extents.empty()) return info;
  const auto sources = recording.topicSources();
  std::int64_t first_ns = std::numeric_limits<std::int64_t>::max(), last_ns = std::numeric_limits<std::int64_t>::min();
  info.first_step = std::numeric_limits<std::uint64_t>::max();
  for (const auto& [topic, e] : extents) {
    first_ns = std::min(first_ns, e.first_sim_time_ns);
    last_ns = std::max(last_ns, e.last_sim_time_ns);
    info.samples += e.samples;
    if (topic == bus::topics::kHealth.name) continue;  // its "step" counts the steps done, no stamp
    info.first_step = std::min(info.first_step, e.first_step);
    info.last_step = std::max(info.last_step, e.last_step);
  }
  info.sim_duration_s = static_cast<double>(last_ns - first_ns) * 1e-9;
  for (const auto& [topic, e] : extents) {
    RecordedTopic t{topic, typeOf(topic), {}, e.samples, 0.0};
    if (const auto it = sources.find(topic); it != sources.end()) t.sources = it->second;
    // Over the run's span, not the topic's own: a topic that fell silent half-way has
    // half its rate, as ros2 bag info reckons over the bag's duration.
    if (info.sim_duration_s > 0.0) t.rate_hz = static_cast<double>(e.samples) / info.sim_duration_s;
    info.topics.push_back(std::move(t));
  }
  if (const auto it = extents.find(std::string(bus::topics::kHealth.name)); it != extents.end()) {
    const auto first = healthWallNs(recording, it->second.first_step, false);
    const auto last = healthWallNs(recording, it->second.last_step, true);
    if (first != std::numeric_limits<std::uint64_t>::max() && last >= first) {
      info.wall_duration_s = static_cast<double>(last - first) * 1e-9;
    }
  }
  return info;
}

nlohmann::ordered_json toJson(const RecordingInfo& info) {
  nlohmann::ordered_json j;
  j["recording"] = info.path;
  j["size_bytes"] = info.size_bytes;
  j["scenario"] = info.scenario;
  j["mode"] = info.mode;
  j["recording_sha256"] = info.digest;
  j["recorder_sha256"] = info.recorded_digest.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(info.recorded_digest);
  j["first_step"] = info.first_step;
  j["last_step"] = info.last_step;
  j["duration_sim_s"] = info.sim_duration_s;
  j["duration_wall_s"] = info.wall_duration_s;
  j["samples"] = info.samples;
  auto& topics = j["topics"] = nlohmann::ordered_json::array();
  for (const auto& t : info.topics) {
    topics.push_back({{"name", t.name}, {"type", t.type}, {"count", t.samples}, {"rate_hz", t.rate_hz},
                      {"sources", t.sources}});
  }
  return j;
}

std::string infoTable(const RecordingInfo& info) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%.1f MiB", static_cast<double>(info.size_bytes) / (1024.0 * 1024.0));
  out << "Recording:     " << info.path << "\n"
      << "Size:          " << line << "\n"
      << "Scenario:      " << info.scenario << " (" << info.mode << ")\n"
      << "Digest:        " << info.digest << " (recording_sha256"
      << (info.changedSinceRecorded() ? "; NOT the recorder's " + info.recorded_digest + ": samples changed since"
          : info.recorded_digest.empty() ? ""
                                         : ", as its recorder kept it")
      << ")\n";
  std::snprintf(line, sizeof line, "%.3f s simulated (steps %llu..%llu), %.3f s of wall clock", info.sim_duration_s,
                static_cast<unsigned long long>(info.first_step), static_cast<unsigned long long>(info.last_step),
                info.wall_duration_s);
  out << "Duration:      " << line << "\n"
      << "Samples:       " << info.samples << "\n"
      << "Topics:\n";
  std::size_t name_width = 5, type_width = 4;
  for (const auto& t : info.topics) {
    name_width = std::max(name_width, t.name.size());
    type_width = std::max(type_width, t.type.size());
  }
  std::snprintf(line, sizeof line, "  %-*s  %-*s  %10s  %10s  %s\n", static_cast<int>(name_width), "TOPIC",
                static_cast<int>(type_width), "TYPE", "SAMPLES", "RATE [Hz]", "SOURCES");
  out << line;
  for (const auto& t : info.topics) {
    std::string sources;
    for (const auto& s : t.sources) sources += (sources.empty() ? "" : ",") + s;
    std::snprintf(line, sizeof line, "  %-*s  %-*s  %10llu  %10.3f  ", static_cast<int>(name_width), t.name.c_str(),
                  static_cast<int>(type_width), t.type.c_str(), static_cast<unsigned long long>(t.samples), t.rate_hz);
    out << line << sources << "\n";
  }
  return out.str();
}

}  // namespace flatsat::analysis
