// SPDX-License-Identifier: Apache-2.0
#include "tools/ReportErrors.hpp"
#include "tools/ReplayCommand.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include "bus/Recording.hpp"
#include "bus/RecordingMeta.hpp"
#include "bus/Security.hpp"
#include "bus/Serialization.hpp"
#include "bus/TimeMaster.hpp"
#include "tools/GrantsCommand.hpp"
#include "tools/ToolBus.hpp"

namespace flatsat::tools {

namespace {

namespace fs = std::filesystem;

struct ReplayOptions {
  std::string recording;
  std::vector<std::string> waits;   ///< NAME or NAME=DIVIDER
  std::vector<std::string> topics;  ///< empty: every stepped topic not from a waited component
  std::string pace = "lockstep";
  std::string capture;
  double timeout_s = 60.0;
  int domain = -1;
};

/// The recorded run's timing, from its recorded step grants.
struct RecordedTiming {
  std::int64_t period_ns = 0;
  std::uint64_t final_step = 0;
};

RecordedTiming recordedTiming(const bus::Recording& recording, const std::string& path) {
  std::optional<msg::StepGrant> first;
  recording.forEach(std::string(bus::topics::kStepGrant.name),
                    [&](std::uint64_t, const std::string&, const std::vector<std::uint8_t>& bytes) {
                      if (!first) first = bus::deserialize<std::remove_cvref_t<decltype(bus::topics::kStepGrant)>>(bytes);
                    });
  if (!first) {
    throw std::runtime_error(path + ": no " + std::string(bus::topics::kStepGrant.name) +
                             " samples: the recording does not say how time advanced");
  }
  return {first->step_period_ns(), first->final_step()};
}

/// One recorded topic published again, sample by sample, at its steps.
class Channel {
 public:
  virtual ~Channel() = default;
  virtual std::uint64_t publish(const bus::Recording& recording, std::uint64_t step) = 0;
};

template <class Def>
class ChannelOf final : public Channel {
 public:
  ChannelOf(bus::Writer<Def>& writer, const Def& def) : writer_(writer), topic_(def.name) {}
  std::uint64_t publish(const bus::Recording& recording, std::uint64_t step) override {
    std::uint64_t n = 0;
    recording.forEachAt(topic_, step, [&](const std::string&, const std::vector<std::uint8_t>& bytes) {
      writer_.write(bus::deserialize<Def>(bytes));
      ++n;
    });
    return n;
  }

 private:
  bus::Writer<Def>& writer_;
  std::string topic_;
};

/// The time master of a replay: at step k it publishes the recorded samples
/// stamped k of the replayed topics, then the grant. In lockstep it waits
/// for the waited components' StepDone and for their outputs stamped k,
/// which it stores into the capture file as they arrive.
class Replayer final : public bus::TimeMaster {
 public:
  Replayer(bus::Bus& bus, bus::NodeOptions options, Timing timing, const bus::Recording& recording,
           const std::vector<std::string>& topics, const std::vector<std::string>& captured,
           bus::Recording* capture)
      : TimeMaster(bus, std::move(options), timing), recording_(recording), capture_(capture) {
    for (const auto& topic : topics) {
      withTopic(topic, [&](const auto& def) {
        channels_.push_back(std::make_unique<ChannelOf<std::remove_cvref_t<decltype(def)>>>(
            addOutput(def), def));
      });
    }
    for (const auto& topic : captured) {
      withTopic(topic, [&](const auto& def) {
        using Def = std::remove_cvref_t<decltype(def)>;
        addTap(def, [this, name = std::string(def.name)](const typename Def::Type& sample) {
          std::lock_guard lock(capture_mutex_);
          capture_->insert(name, sample.header().step(), bus::text(sample.header().source()),
                           sample.header().sim_time_ns(), bus::serialize<Def>(sample));
        });
      });
    }
  }
  std::uint64_t published() const { return published_; }

 private:
  void publishStep(const bus::StepContext& ctx) override {
    for (auto& channel : channels_) published_ += channel->publish(recording_, ctx.step);
  }
  void advance(const bus::StepContext&) override {}

  const bus::Recording& recording_;
  bus::Recording* capture_;
  std::mutex capture_mutex_;  // Fast DDS threads of several topics insert
  std::vector<std::unique_ptr<Channel>> channels_;
  std::uint64_t published_ = 0;
};

/// Per captured topic: how the re-run component's samples compare with the
/// recorded ones, byte for byte, by (step, source).
void compare(const bus::Recording& recorded, const bus::Recording& captured,
             const std::string& topic) {
  std::map<std::pair<std::uint64_t, std::string>, std::vector<std::uint8_t>> got;
  captured.forEach(topic, [&](std::uint64_t step, const std::string& source, const auto& bytes) {
    got[{step, source}] = bytes;
  });
  std::uint64_t identical = 0, differ = 0, missing = 0, first_differ = 0;
  recorded.forEach(topic, [&](std::uint64_t step, const std::string& source, const auto& bytes) {
    auto it = got.find({step, source});
    if (it == got.end()) {
      ++missing;
    } else if (it->second == bytes) {
      ++identical;
    } else if (differ++ == 0) {
      first_differ = step;
    }
  });
  std::printf("%s: %zu captured, %llu identical to the recording, %llu differ", topic.c_str(),
              got.size(), static_cast<unsigned long long>(identical),
              static_cast<unsigned long long>(differ));
  if (differ > 0) std::printf(" (first at step %llu)", static_cast<unsigned long long>(first_differ));
  std::printf(", %llu not re-published\n", static_cast<unsigned long long>(missing));
}

int replay(const ReplayOptions& o) {
  if (!fs::is_regular_file(o.recording)) {
    std::cerr << "error: " << o.recording << ": no such recording\n";
    return 2;
  }
  if (o.pace != "lockstep" && o.pace != "wall") {
    std::cerr << "error: --pace: '" << o.pace << "' is neither lockstep nor wall\n";
    return 2;
  }
  const bus::Recording recording(o.recording, bus::Recording::Access::kRead);
  if (const auto every = recording.meta(bus::meta::kRecordEverySteps); !every.empty()) {
    std::cerr << "error: " << o.recording << ": recorded every " << every
              << " steps only (recorder record_every_steps): a replay needs every step\n";
    return 2;
  }
  const auto timing = recordedTiming(recording, o.recording);
  const std::string schedule_text = recording.meta(bus::meta::kSchedule);
  const bus::Schedule recorded_schedule =
      bus::meta::parseSchedule(schedule_text, o.recording + ": meta " + bus::meta::kSchedule);

  bus::NodeOptions node;
  node.name = "replay";
  node.schedule[node.name] = 1;
  for (const auto& wait : o.waits) {
    const auto eq = wait.find('=');
    if (eq != std::string::npos) {
      const auto parsed = bus::meta::parseSchedule(wait, "--wait");
      node.schedule.insert(parsed.begin(), parsed.end());
    } else if (auto it = recorded_schedule.find(wait); it != recorded_schedule.end()) {
      node.schedule.insert(*it);
    } else {
      std::cerr << "error: --wait " << wait << ": not in the recorded rig's schedule ("
                << (schedule_text.empty() ? "none recorded" : schedule_text)
                << "); give --wait " << wait << "=DIVIDER\n";
      return 2;
    }
  }
  node.pacing = o.pace == "wall" ? bus::Pacing::kPaced : bus::Pacing::kLockstep;
  node.period = std::chrono::nanoseconds(timing.period_ns);
  node.peer_timeout = node.step_timeout =
      std::chrono::milliseconds(std::llround(o.timeout_s * 1e3));

  // Replayed: the chosen topics, else every recorded stepped topic that no
  // waited component produces; captured: what the waited components produce.
  const auto sources = recording.topicSources();
  std::vector<std::string> topics, captured;
  for (const auto& name : o.topics) {
    if (!withTopic(name, [&](const auto& def) { topics.emplace_back(def.name); })) {
      std::cerr << "error: unknown topic '" << name << "'; topics: " << registryTopicNames() << "\n";
      return 2;
    }
    if (!sources.count(topics.back())) {
      std::cerr << "error: " << o.recording << ": no " << topics.back() << " samples recorded\n";
      return 2;
    }
  }
  bus::forEachTopic([&](const auto& def) {
    if (def.qos != bus::QosKind::kStepped || !sources.count(std::string(def.name))) return;
    const bool waited = node.schedule.count(std::string(def.producer)) != 0;
    if (waited) {
      captured.emplace_back(def.name);
    } else if (o.topics.empty()) {
      topics.emplace_back(def.name);
    }
  });
  std::unique_ptr<bus::Recording> capture;
  if (!o.capture.empty()) {
    if (fs::exists(o.capture)) {
      std::cerr << "error: " << o.capture << " exists; choose another --capture\n";
      return 2;
    }
    capture = std::make_unique<bus::Recording>(o.capture, bus::Recording::Access::kCreate);
    capture->setMeta(bus::meta::kScenario, recording.meta(bus::meta::kScenario) + " (replayed)");
  }

  bus::BusOptions bus_options;
  bus_options.domain_id = resolveDomain(o.domain);
  bus::useNetwork(bus_options, bus::networkFromEnvironment());
  bus_options.identity = kReplayIdentity;  // DDS Security: its own grant (tools/GrantsCommand.hpp)
  bus_options.participant_name = "flatsat-replay";
  // A component configured paced expects its producers' liveliness lease.
  bus_options.tuning.watch_liveliness = recording.meta(bus::meta::kMode) == "paced";
  if (const auto lease = recording.meta(bus::meta::kLeaseMs); !lease.empty()) {
    bus_options.tuning.lease = std::chrono::milliseconds(std::stoll(lease));
  }
  bus::Bus bus(bus_options);
  Replayer replayer(bus, node, {timing.period_ns, timing.final_step}, recording, topics,
                    capture ? captured : std::vector<std::string>{}, capture.get());
  std::cerr << "flatsat replay: steps 0.." << timing.final_step << " of " << o.recording << " ("
            << topics.size() << " topics) on domain " << bus_options.domain_id << ", "
            << (node.pacing == bus::Pacing::kPaced ? "at wall pace" : "in lockstep")
            << (node.schedule.size() > 1 ? ", waiting for" : "");
  for (const auto& [name, divider] : node.schedule) {
    if (name != node.name) std::cerr << " " << name;
  }
  std::cerr << "\n";
  try {
    replayer.run();
  } catch (const bus::NodeFailure& failure) {
    std::cerr << "error: " << failure.what() << "\n";
    return 1;
  }
  // Paced, nobody was waited for: give the last outputs a moment to come in.
  if (node.pacing == bus::Pacing::kPaced && capture) {
    std::this_thread::sleep_for(std::chrono::nanoseconds(timing.period_ns) * 5);
  }
  std::printf("replayed %llu samples on %zu topics over %llu steps\n",
              static_cast<unsigned long long>(replayer.published()), topics.size(),
              static_cast<unsigned long long>(timing.final_step + 1));
  if (capture) {
    capture->commit();
    for (const auto& topic : captured) compare(recording, *capture, topic);
  }
  return 0;
}

}  // namespace

CLI::App* addReplayCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ReplayOptions>();
  auto* cmd = app.add_subcommand(
      "replay", "publish a recording back onto the bus to re-run components against it");
  cmd->add_option("recording", options->recording, "recording.sqlite of a run")->required();
  cmd->add_option("-w,--wait", options->waits,
                  "a component re-run against the recording (repeatable): NAME, its divider "
                  "from the recorded schedule, or NAME=DIVIDER; its outputs are not replayed");
  cmd->add_option("-t,--topic", options->topics,
                  "replay only this topic (repeatable; default: every recorded stepped topic "
                  "that no --wait component produces)");
  cmd->add_option("--pace", options->pace,
                  "lockstep (default): each step waits for the --wait components' StepDone; "
                  "wall: one step per recorded step period of wall time");
  cmd->add_option("--capture", options->capture,
                  "record what the --wait components publish into this new file (same format) "
                  "and compare it with the recording");
  cmd->add_option("--timeout", options->timeout_s,
                  "[s] give up when a component is not ready or does not step for this long")
      ->check(CLI::PositiveNumber);
  addDomainOption(*cmd, options->domain);
  cmd->footer(
      "The replay is the time master: start the component(s) on the same domain with the\n"
      "run's scenario.yaml, e.g.\n"
      "  flatsat-estimator --scenario RUN/scenario.yaml --out /tmp/x &\n"
      "  flatsat replay RUN/recording.sqlite --wait estimator --capture /tmp/x/re.sqlite\n"
      "Grants follow the recorded step grants (period, final step). With --capture it\n"
      "prints, per captured topic, how many samples are byte-identical to the recording.");
  cmd->callback([options, &exit_code] { runReportingErrors(exit_code, [&] { return replay(*options); }); });
  return cmd;
}

}  // namespace flatsat::tools
