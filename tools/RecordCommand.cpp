// SPDX-License-Identifier: Apache-2.0
#include "tools/ReportErrors.hpp"
#include "tools/RecordCommand.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>

#include "bus/Recording.hpp"
#include "bus/RecordingMeta.hpp"
#include "bus/Serialization.hpp"
#include "tools/ToolBus.hpp"

namespace flatsat::tools {

namespace {

namespace fs = std::filesystem;

constexpr double kCommitPeriodS = 0.5;  // [s] a crash of the tool loses at most this much
/// [s] After the stop grant, samples still in flight from the other writers
/// (each component's last outputs travel on their own connections).
constexpr double kDrainS = 1.0;

struct RecordOptions {
  std::string out;
  std::vector<std::string> topics;  ///< empty: every registry topic
  double seconds = 0.0;             ///< [s] wall time limit, 0: none
  int domain = -1;
  bool force = false;               ///< replace an existing file
};

/// The recording and SQLite's files beside it.
void removeRecording(const std::string& path) {
  for (const std::string suffix : {"", "-wal", "-shm"}) fs::remove(path + suffix);
}

/// The file and what went into it; readers store from Fast DDS threads.
class Sink {
 public:
  explicit Sink(const std::string& path) : recording_(path, bus::Recording::Access::kCreate) {}
  void store(const std::string& topic, const msg::SampleHeader& header,
             const std::vector<std::uint8_t>& payload) {
    std::lock_guard lock(mutex_);
    recording_.insert(topic, header.step(), bus::text(header.source()), header.sim_time_ns(),
                      payload);
    ++counts_[topic];
  }
  void commit() {
    std::lock_guard lock(mutex_);
    recording_.commit();
  }
  void setMeta(const std::string& key, const std::string& value) {
    std::lock_guard lock(mutex_);
    recording_.setMeta(key, value);
  }
  std::map<std::string, std::uint64_t> counts() const {
    std::lock_guard lock(mutex_);
    return counts_;
  }

 private:
  mutable std::mutex mutex_;
  bus::Recording recording_;
  std::map<std::string, std::uint64_t> counts_;
};

bool chosen(const RecordOptions& o, std::string_view topic) {
  return o.topics.empty() || std::any_of(o.topics.begin(), o.topics.end(), [&](const auto& t) {
           return t == topic || t == shortTopicName(topic);
         });
}

int record(const RecordOptions& o) {
  for (const auto& topic : o.topics) {
    if (!withTopic(topic, [](const auto&) {})) {
      std::cerr << "error: unknown topic '" << topic << "'; topics: " << registryTopicNames() << "\n";
      return 2;
    }
  }
  if (fs::exists(o.out) && !o.force) {
    std::cerr << "error: " << o.out << " exists; choose another --out, or --force to replace it\n";
    return 2;
  }
  if (o.force) removeRecording(o.out);
  if (fs::path(o.out).has_parent_path()) fs::create_directories(fs::path(o.out).parent_path());
  auto owned_sink = std::make_unique<Sink>(o.out);
  Sink& sink = *owned_sink;
  ToolBus tool_bus("record", o.domain);
  sink.setMeta("recorded_by", "flatsat record");
  sink.setMeta("domain", std::to_string(tool_bus.domain()));
  std::atomic<bool> stopped{false};
  // Readers with the registry's QoS, as the rig's recorder has: reliable
  // and transient-local, so the writers' kept history (the last steps before
  // the tool matched) comes too, and exclusive ownership picks the same
  // producer the rig's components listen to.
  std::vector<std::shared_ptr<void>> readers;
  bus::forEachTopic([&](const auto& def) {
    using Def = std::remove_cvref_t<decltype(def)>;
    const bool wanted = chosen(o, def.name);
    const bool is_grant = def.name == bus::topics::kStepGrant.name;
    if (!wanted && !is_grant) return;
    readers.push_back(std::make_shared<bus::Reader<Def>>(
        tool_bus.bus(), def,
        [&sink, &stopped, wanted, topic = std::string(def.name)](const typename Def::Type& sample) {
          if (wanted) sink.store(topic, sample.header(), bus::serialize<Def>(sample));
          if constexpr (std::is_same_v<typename Def::Type, msg::StepGrant>) {
            if (sample.stop()) stopped = true;
          }
        }));
  });
  std::cerr << "flatsat record: " << (o.topics.empty() ? "every topic" : "chosen topics")
            << " on domain " << tool_bus.domain() << " into " << o.out
            << " (until the rig stops" << (o.seconds > 0 ? ", " + std::to_string(o.seconds) + " s" : "")
            << " or Ctrl-C)\n";
  const auto start = Clock::now();
  for (;;) {
    if (!sleepUnlessInterrupted(kCommitPeriodS)) break;
    sink.commit();
    if (stopped) {
      sleepUnlessInterrupted(kDrainS);
      break;
    }
    if (o.seconds > 0 &&
        Clock::now() - start > std::chrono::duration<double>(o.seconds)) {
      break;
    }
  }
  readers.clear();  // no callback may store after this
  sink.commit();
  const auto counts = sink.counts();
  std::uint64_t total = 0;
  for (const auto& [topic, n] : counts) {
    std::printf("%s: %llu samples\n", topic.c_str(), static_cast<unsigned long long>(n));
    total += n;
  }
  std::printf("recorded %llu samples on %zu topics%s\n", static_cast<unsigned long long>(total),
              counts.size(), stopped ? " (the rig stopped)" : "");
  if (total == 0) {
    owned_sink.reset();  // closed before it goes: an empty recording is no recording
    removeRecording(o.out);
    std::cerr << "flatsat record: nothing came on domain " << tool_bus.domain() << "; " << o.out
              << " not kept\n";
    return 1;
  }
  return 0;
}

}  // namespace

CLI::App* addRecordCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<RecordOptions>();
  auto* cmd = app.add_subcommand("record", "attach to a running rig and record its topics");
  cmd->add_option("-o,--out", options->out, "recording file to create (SQLite)")->required();
  cmd->add_option("-t,--topic", options->topics,
                  "record only this topic (repeatable; flatsat/gyro or gyro; default: all)");
  cmd->add_option("-s,--seconds", options->seconds,
                  "[s] stop after this much wall time (default: when the rig stops)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--force", options->force, "replace --out when it exists");
  addDomainOption(*cmd, options->domain);
  cmd->footer(
      "The file has the format of a run's recording.sqlite: export, plot and replay\n"
      "read it. Readers take the rig's own QoS (reliable, transient-local), so the\n"
      "last 64 steps before the tool joined come too. Recording stops 1 s after the\n"
      "rig's stop grant, on --seconds or on Ctrl-C; committed every 0.5 s. When\n"
      "nothing came, no file is left.");
  cmd->callback([options, &exit_code] { runReportingErrors(exit_code, [&] { return record(*options); }); });
  return cmd;
}

}  // namespace flatsat::tools
