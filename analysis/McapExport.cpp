// SPDX-License-Identifier: Apache-2.0
#include "analysis/McapExport.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "analysis/Mcap.hpp"
#include "analysis/McapSchemas.hpp"
#include "bus/Recording.hpp"
#include "bus/Scenario.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "msg/MsgJson.hpp"

namespace flatsat::analysis {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

constexpr const char* kMetadataName = "flatsat";

/// The scenario's epoch from the run directory's scenario.yaml ("" when the
/// recording has no run directory around it).
std::string epochOf(const std::string& recording) {
  const fs::path scenario = fs::absolute(recording).parent_path() / "scenario.yaml";
  if (!fs::exists(scenario)) return "";
  try {
    const YAML::Node root = bus::loadScenarioYaml(scenario.string());
    if (root["orbit"] && root["orbit"]["epoch_utc"]) return root["orbit"]["epoch_utc"].as<std::string>();
  } catch (const std::exception&) {
    // An unreadable scenario leaves the epoch out; the times stay simulated seconds.
  }
  return "";
}

Json stamp(std::int64_t ns) {
  const std::int64_t t = std::max<std::int64_t>(0, ns);
  return {{"sec", t / 1'000'000'000}, {"nsec", t % 1'000'000'000}};
}

/// foxglove.FrameTransform of the body in the inertial frame: q_inertial_body
/// maps body vectors to inertial ones (idl/Common.idl), which is the child
/// frame's orientation in its parent that the schema asks for; the origin
/// stays at the inertial origin so the 3D panel shows the spacecraft turning.
std::string frameTransform(std::int64_t ns, const char* child, const std::array<double, 4>& q) {
  // Written directly rather than through a JSON tree: two of these per step
  // were a third of a long recording's export. %.17g reads back to the same double.
  const std::int64_t t = std::max<std::int64_t>(0, ns);
  char text[400];
  const int n = std::snprintf(text, sizeof text,
                              "{\"timestamp\":{\"sec\":%lld,\"nsec\":%lld},\"parent_frame_id\":\"inertial\","
                              "\"child_frame_id\":\"%s\",\"translation\":{\"x\":0.0,\"y\":0.0,\"z\":0.0},"
                              "\"rotation\":{\"x\":%.17g,\"y\":%.17g,\"z\":%.17g,\"w\":%.17g}}",
                              static_cast<long long>(t / 1'000'000'000), static_cast<long long>(t % 1'000'000'000),
                              child, q[1], q[2], q[3], q[0]);
  return std::string(text, static_cast<std::size_t>(n));
}

/// JSON has no NaN: a quaternion that is not finite gets no transform.
bool finite(const std::array<double, 4>& q) {
  return std::all_of(q.begin(), q.end(), [](double v) { return std::isfinite(v); });
}

// foxglove.LogLevel
constexpr int kInfo = 2, kWarning = 3, kError = 4;

std::string logLine(std::int64_t ns, int level, const std::string& message, const std::string& name) {
  return Json{{"timestamp", stamp(ns)}, {"level", level}, {"message", message}, {"name", name}, {"file", ""},
              {"line", 0}}
      .dump();
}

std::string faultMessage(const Json& event) {
  std::string m = std::string("fault ") + event["kind"].get<std::string>() +
                  (event["active"].get<bool>() ? " began" : " stopped");
  if (!event["topic"].get<std::string>().empty()) m += " on " + event["topic"].get<std::string>();
  m += ", channel " + std::to_string(event["channel"].get<long>());
  m += ", magnitude " + Json(event["magnitude"]).dump();
  return m;
}

}  // namespace

bool isMcap(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, sizeof magic);
  return in && std::string(magic, 8) == std::string("\x89MCAP0\r\n", 8);
}

namespace {

McapExportCounts writeMcap(const std::string& path, const std::string& out, const std::string& library) {
  const RecordingInfo info = describeRecording(path);
  const bus::Recording recording(path, bus::Recording::Access::kRead);
  // A health sample is stamped with its component's steps done, not a time:
  // it is placed at the rig's step it reached (Health.step_reached), in the
  // run's own step length.
  const double ns_per_step = info.last_step > info.first_step
                                 ? info.sim_duration_s * 1e9 / static_cast<double>(info.last_step - info.first_step)
                                 : 0.0;
  McapWriter writer(out, library);
  McapExportCounts counts;
  writer.addMetadata(kMetadataName, {{"scenario", info.scenario},
                                     {"mode", info.mode},
                                     {"recording_sha256", info.digest},
                                     {"epoch_utc", epochOf(path)},
                                     {"time", "log and publish times: simulated time since epoch_utc [ns]"},
                                     {"first_step", std::to_string(info.first_step)},
                                     {"last_step", std::to_string(info.last_step)},
                                     {"wall_duration_s", Json(info.wall_duration_s).dump()},
                                     {"recording", fs::path(path).filename().string()}});
  std::map<std::string, std::uint16_t> channel_of;
  for (const auto& t : info.topics) {
    const auto idl = omgIdlSchema(t.type);
    if (idl.empty()) continue;  // not a registry topic: nothing tells how to read it
    std::string sources;
    for (const auto& s : t.sources) sources += (sources.empty() ? "" : ",") + s;
    channel_of[t.name] =
        writer.addChannel(writer.addSchema(t.type, "omgidl", std::string(idl)), t.name, "cdr", {{"sources", sources}});
  }
  const auto tf_schema = writer.addSchema("foxglove.FrameTransform", "jsonschema",
                                          std::string(foxgloveJsonSchema("foxglove.FrameTransform")));
  const auto truth_frames = writer.addChannel(tf_schema, kMcapTruthFrames, "json");
  const auto estimate_frames = writer.addChannel(tf_schema, kMcapEstimateFrames, "json");
  const auto log = writer.addChannel(
      writer.addSchema("foxglove.Log", "jsonschema", std::string(foxgloveJsonSchema("foxglove.Log"))), kMcapLog,
      "json");
  counts.channels = channel_of.size() + 3;

  auto write = [&](std::uint16_t channel, std::int64_t ns, const std::string& text) {
    const auto t = static_cast<std::uint64_t>(std::max<std::int64_t>(0, ns));
    writer.addMessage(channel, t, t, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
    ++counts.messages;
  };
  std::map<std::string, std::string> health_seen;  // source -> "STATE: message"
  recording.forEachSample([&](const std::string& topic, std::uint64_t /*step*/, const std::string& source,
                              std::int64_t sim_time_ns, const std::vector<std::uint8_t>& payload) {
    const auto channel = channel_of.find(topic);
    if (channel == channel_of.end()) return;
    const bool health = topic == bus::topics::kHealth.name;
    Json h;
    if (health) h = msg::toJson(bus::deserialize<std::remove_cvref_t<decltype(bus::topics::kHealth)>>(payload));
    const std::int64_t ns =
        health ? std::llround(static_cast<double>(h["step_reached"].get<std::uint64_t>()) * ns_per_step) : sim_time_ns;
    const auto t = static_cast<std::uint64_t>(std::max<std::int64_t>(0, ns));
    writer.addMessage(channel->second, t, t, payload.data(), payload.size());
    ++counts.messages;
    if (topic == bus::topics::kTruth.name) {
      const auto truth = bus::deserialize<std::remove_cvref_t<decltype(bus::topics::kTruth)>>(payload);
      if (finite(truth.q_inertial_body())) write(truth_frames, ns, frameTransform(ns, "body", truth.q_inertial_body()));
    } else if (topic == bus::topics::kAttitudeEstimate.name) {
      const auto estimate = bus::deserialize<std::remove_cvref_t<decltype(bus::topics::kAttitudeEstimate)>>(payload);
      if (finite(estimate.q_inertial_body())) {
        write(estimate_frames, ns, frameTransform(ns, "body_estimate", estimate.q_inertial_body()));
      }
    } else if (topic == bus::topics::kFaultEvent.name) {
      const auto event = msg::toJson(bus::deserialize<std::remove_cvref_t<decltype(bus::topics::kFaultEvent)>>(payload));
      write(log, ns, logLine(ns, event["active"].get<bool>() ? kWarning : kInfo, faultMessage(event), source));
    } else if (health) {
      const std::string state = h["state"].get<std::string>();
      const std::string said = state + (h["message"].get<std::string>().empty() ? "" : ": " + h["message"].get<std::string>());
      auto& seen = health_seen[source];
      if (said != seen) write(log, ns, logLine(ns, state == "FAILED" ? kError : kInfo, said, source));
      seen = said;
    }
  });
  writer.close();
  return counts;
}

}  // namespace

McapExportCounts exportMcap(const std::string& path, const std::string& out, const std::string& library) {
  // Written aside and renamed when whole: an export that fails part-way
  // leaves no file at OUT, and an earlier OUT stays as it was.
  const std::string partial = out + ".partial";
  try {
    const auto counts = writeMcap(path, partial, library);
    fs::rename(partial, out);
    return counts;
  } catch (...) {
    std::error_code ignored;
    fs::remove(partial, ignored);
    throw;
  }
}

RecordingInfo describeMcap(const std::string& path) {
  const McapSummary summary = readMcapSummary(path);
  RecordingInfo info;
  info.path = path;
  info.size_bytes = fs::file_size(path);
  const auto it = summary.metadata.find(kMetadataName);
  const McapMap meta = it == summary.metadata.end() ? McapMap{} : it->second;
  auto value = [&](const char* key) { return meta.count(key) ? meta.at(key) : std::string(); };
  info.scenario = value("scenario");
  info.mode = value("mode");
  info.digest = value("recording_sha256");
  if (!value("first_step").empty()) info.first_step = std::stoull(value("first_step"));
  if (!value("last_step").empty()) info.last_step = std::stoull(value("last_step"));
  if (!value("wall_duration_s").empty()) info.wall_duration_s = std::stod(value("wall_duration_s"));
  info.sim_duration_s = static_cast<double>(summary.last_ns - summary.first_ns) * 1e-9;
  info.samples = summary.messages;
  for (const auto& ch : summary.channels) {
    RecordedTopic t{ch.topic, ch.schema_name, {}, ch.messages, 0.0};
    if (const auto s = ch.metadata.find("sources"); s != ch.metadata.end()) {
      std::string rest = s->second;
      for (std::size_t comma; !rest.empty(); rest = comma == std::string::npos ? "" : rest.substr(comma + 1)) {
        comma = rest.find(',');
        t.sources.insert(rest.substr(0, comma));
      }
    }
    if (info.sim_duration_s > 0) t.rate_hz = static_cast<double>(ch.messages) / info.sim_duration_s;
    info.topics.push_back(std::move(t));
  }
  std::sort(info.topics.begin(), info.topics.end(),
            [](const RecordedTopic& a, const RecordedTopic& b) { return a.name < b.name; });
  return info;
}

}  // namespace flatsat::analysis
