// SPDX-License-Identifier: Apache-2.0
#include "tools/ReportErrors.hpp"
#include "tools/ExportCommand.hpp"
#include "analysis/McapExport.hpp"
#include "flatsat_version.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>

#include "bus/Recording.hpp"
#include "bus/Serialization.hpp"
#include "tools/ToolBus.hpp"

namespace fs = std::filesystem;

namespace flatsat::tools {

namespace {

struct ExportOptions {
  std::string recording;
  bool csv = false;
  bool json = false;
  std::string mcap;                 ///< --mcap OUT: one MCAP file of every topic
  std::vector<std::string> topics;  ///< empty: every recorded topic
  std::string out;                  ///< empty: <recording's folder>/export
};

/// RFC 4180: quoted when it holds a separator, a quote or a line break.
std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string csvValue(const nlohmann::ordered_json& v) {
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_string()) return csvField(v.get<std::string>());
  if (v.is_number_float() && !std::isfinite(v.get<double>())) {
    return std::isnan(v.get<double>()) ? "nan" : (v.get<double>() > 0 ? "inf" : "-inf");
  }
  return v.dump();  // shortest text that reads back to the same double
}

template <class Def>
std::uint64_t exportTopic(const bus::Recording& recording, const Def& def, bool csv,
                          const fs::path& file) {
  using Sample = typename Def::Type;
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  const auto& leaves = msg::leafFields<Sample>();
  if (csv) {
    for (std::size_t i = 0; i < leaves.size(); ++i) {
      std::string name(leaves[i].name);
      if (!leaves[i].unit.empty()) name += " [" + std::string(leaves[i].unit) + "]";
      out << (i ? "," : "") << csvField(name);
    }
    out << "\n";
  }
  std::uint64_t rows = 0;
  std::vector<std::pair<std::string, const nlohmann::ordered_json*>> flat;
  recording.forEach(std::string(def.name), [&](std::uint64_t step, const std::string&,
                                               const std::vector<std::uint8_t>& payload) {
    const auto json = msg::toJson(bus::deserialize<Def>(payload));
    ++rows;
    if (!csv) {
      out << json.dump() << "\n";
      return;
    }
    flat.clear();
    flattenJson(json, "", flat);
    if (flat.size() != leaves.size()) {
      throw std::runtime_error(std::string(def.name) + " step " + std::to_string(step) + ": " +
                               std::to_string(flat.size()) + " values for " +
                               std::to_string(leaves.size()) + " columns");
    }
    for (std::size_t i = 0; i < flat.size(); ++i) out << (i ? "," : "") << csvValue(*flat[i].second);
    out << "\n";
  });
  if (!out.flush()) throw std::runtime_error("cannot write " + file.string());
  return rows;
}

int exportRecording(const ExportOptions& o) {
  if (!fs::is_regular_file(o.recording)) {
    std::cerr << "error: " << o.recording << ": no such recording\n";
    return 2;
  }
  if (!o.mcap.empty()) {
    const auto start = std::chrono::steady_clock::now();
    const auto counts = analysis::exportMcap(o.recording, o.mcap, std::string("flatsat ") + kFlatsatVersion);
    std::printf("%s: %llu messages on %llu channels in %.2f s\n", o.mcap.c_str(),
                static_cast<unsigned long long>(counts.messages), static_cast<unsigned long long>(counts.channels),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return 0;
  }
  for (const auto& topic : o.topics) {
    if (!withTopic(topic, [](const auto&) {})) {
      std::cerr << "error: unknown topic '" << topic << "'; topics: " << registryTopicNames()
                << "\n";
      return 2;
    }
  }
  const fs::path out_dir =
      o.out.empty() ? fs::absolute(o.recording).parent_path() / "export" : fs::path(o.out);
  fs::create_directories(out_dir);
  const bus::Recording recording(o.recording, bus::Recording::Access::kRead);
  std::size_t files = 0;
  bus::forEachTopic([&](const auto& def) {
    const bool chosen =
        o.topics.empty() || std::any_of(o.topics.begin(), o.topics.end(), [&](const auto& t) {
          return t == def.name || t == shortTopicName(def.name);
        });
    if (!chosen) return;
    if (recording.count(std::string(def.name)) == 0) {
      if (!o.topics.empty()) std::cerr << "flatsat export: no " << def.name << " samples recorded\n";
      return;
    }
    const fs::path file =
        out_dir / (std::string(shortTopicName(def.name)) + (o.csv ? ".csv" : ".jsonl"));
    const auto rows = exportTopic(recording, def, o.csv, file);
    std::cout << file.string() << ": " << rows << " samples of " << def.name << "\n";
    ++files;
  });
  if (files == 0) {
    std::cerr << "error: nothing to export from " << o.recording << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

CLI::App* addExportCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ExportOptions>();
  auto* cmd = app.add_subcommand(
      "export", "write a recording's topics as CSV or JSON lines, one file per topic");
  cmd->add_option("recording", options->recording, "recording.sqlite of a run")->required();
  auto* csv = cmd->add_flag("--csv", options->csv,
                            "CSV: a header row of field names with units ('b_body_T[0] [T]'), "
                            "one row per sample; booleans 0/1");
  auto* json = cmd->add_flag("--json", options->json,
                             "JSON lines: one object per sample, fields as in the IDL");
  auto* mcap = cmd->add_option("--mcap", options->mcap,
                               "one MCAP file of every topic (omgidl schemas, CDR as recorded, zstd chunks, "
                               "indexed) for Foxglove, Lichtblick and the mcap tools");
  csv->excludes(json);
  mcap->excludes(csv)->excludes(json);
  cmd->add_option("-t,--topic", options->topics,
                  "only this topic (repeatable; flatsat/truth or truth)");
  cmd->add_option("-o,--out", options->out,
                  "output folder (default: 'export' next to the recording)");
  cmd->footer(
      "Files are named after the topic: truth.csv, gyro.jsonl, ... Samples come in\n"
      "step order; columns and fields follow the IDL (idl/*.idl), units from its\n"
      "'// [unit]' comments. --mcap writes one file: a channel per recorded topic, and\n"
      "for viewing flatsat/tf/truth and flatsat/tf/estimate (foxglove.FrameTransform)\n"
      "and flatsat/log (foxglove.Log: faults, health changes); times are simulated.");
  cmd->callback([options, &exit_code] {
    if (options->mcap.empty() && options->csv == options->json) {
      std::cerr << "error: export: give --csv, --json or --mcap OUT\n";
      exit_code = 2;
      return;
    }
    runReportingErrors(exit_code, [&] { return exportRecording(*options); });
  });
  return cmd;
}

}  // namespace flatsat::tools
