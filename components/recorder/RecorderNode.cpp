// SPDX-License-Identifier: Apache-2.0
#include "components/recorder/RecorderNode.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include <spdlog/spdlog.h>

#include "bus/RecordingMeta.hpp"
#include "bus/Serialization.hpp"
#include "components/Processes.hpp"

namespace flatsat::recorder {

namespace {
/// [s] How long a health, command or liveliness change may wait for the next
/// step's batch to the live feed's watchers.
constexpr auto kFeedQuiet = std::chrono::milliseconds(250);
/// A commit rewrites the pages it touched into the WAL: a composed rig, at
/// 170,000 steps a second, committed 345 times a second at 500 steps a
/// transaction, 0.6 s of a simulated day's system time. A crash loses at
/// most this much of the run besides.
constexpr auto kCommitAtMostEvery = std::chrono::milliseconds(100);

SampleFiguresFactory& figuresFactory() {
  static SampleFiguresFactory factory;
  return factory;
}
}  // namespace

void setSampleFiguresFactory(SampleFiguresFactory factory) { figuresFactory() = std::move(factory); }

std::unique_ptr<SampleFigures> makeSampleFigures(const bus::Scenario& scenario) {
  return figuresFactory() ? figuresFactory()(scenario) : nullptr;
}

std::vector<std::string> RecorderParams::validate() const {
  std::vector<std::string> problems;
  if (path.empty()) problems.push_back("path: no recording file (give --out)");
  if (commit_every_steps < 1 || commit_every_steps > 100000) {
    problems.push_back("commit_every_steps: must be in 1..100000");
  }
  if (record_every_steps < 1 || record_every_steps > 100000) {
    problems.push_back("record_every_steps: must be in 1..100000");
  }
  return problems;
}

RecorderNode::RecorderNode(bus::Bus& bus, bus::NodeOptions options, const RecorderParams& params)
    : Component(bus, std::move(options)),
      params_(params),
      // A composed rig is one process, and nothing of it reads the recording while it runs.
      recording_(params.path, bus::Recording::Access::kCreate,
                 bus.localHub() != nullptr ? bus::Recording::Journal::kRollback : bus::Recording::Journal::kWal) {
  // A composed rig holds no socket (docs/architecture.md, "Composed mode"), and has no bus to watch.
  if (bus.localHub() == nullptr) {
    try {
      live_feed_ = std::make_unique<bus::LiveFeedServer>(bus::liveFeedName(bus.domainId()));
    } catch (const bus::LiveFeedError& e) {
      spdlog::info("{}: no live feed ({}); watchers read the bus themselves", name(), e.what());
    }
  }
  bus::forEachTopic([this](const auto& def) {
    // Stepped data whose producer runs in this rig; the protocol topics
    // (grant, done) are bookkeeping, not data.
    if (def.qos == bus::QosKind::kStepped && options_.schedule.count(std::string(def.producer))) {
      record(def);
    }
  });
  health_ = recordAsItComes(bus, bus::topics::kHealth, [this](const std::string& source, bool alive) {
    if (!feedWatched()) return;
    live_feed_->liveliness(source, alive);
    live_feed_->flushUnlessRecent(kFeedQuiet);
  });
  fault_commands_ = recordAsItComes(bus, bus::topics::kFaultCmd);
  fault_events_ = recordAsItComes(bus, bus::topics::kFaultEvent);
  mode_commands_ = recordAsItComes(bus, bus::topics::kUnloadingModeCmd);
  param_commands_ = recordAsItComes(bus, bus::topics::kParamCmd);
  acks_ = recordAsItComes(bus, bus::topics::kCommandAck);
  // The grants of steps 0..final, not the closing "stop": it races the
  // recorder's own shutdown, and a recording must not depend on who won.
  observeGrants([this](const msg::StepGrant& grant) {
    // A grant sent again after a stall (bus::kResendAfter) is recorded once.
    if (grant.stop()) return;
    if (last_grant_ && grant.header().step() <= *last_grant_) return;
    last_grant_ = grant.header().step();
    const bool kept = recorded(grant.header().step());
    if (!kept && !feedWatched()) return;
    const auto payload = bus::serialize<std::remove_cvref_t<decltype(bus::topics::kStepGrant)>>(grant);
    if (kept) store(std::string(bus::topics::kStepGrant.name), grant.header(), payload);
    feed(std::string(bus::topics::kStepGrant.name), grant.header(), payload, false);
  });
  if (params_.figures) {
    // On the recording's writer thread: the figures cost the step nothing.
    recording_.observeStored([this](const bus::StoredSample& sample) {
      if (!params_.figures) return;
      try {
        params_.figures->add(sample);
      } catch (const std::exception& e) {
        figures_failure_ = std::string(sample.topic) + " at step " + std::to_string(sample.step) + ": " + e.what();
        params_.figures.reset();
      }
    });
    recording_.keepOnClose(bus::meta::kFigures, [this] { return figuresJson(); });
  }
  for (const auto& [key, value] : params.meta) recording_.setMeta(key, value);
  if (const auto after = recording_.meta(bus::meta::kResumeAfterStep); !after.empty()) {
    resume_after_ = std::stoull(after);
    spdlog::info("{}: resuming: the samples of steps 0..{} are checked against the recording, not stored again",
                 name(), *resume_after_);
  }
}

bool RecorderNode::recordedAlready(const std::string& topic, const msg::SampleHeader& header,
                                   const std::vector<std::uint8_t>& payload) {
  if (!resume_after_ || header.step() > *resume_after_) return false;
  if (topic == bus::topics::kHealth.name) return true;  // wall-clock data: never the same twice
  if (recording_.holds(topic, header.step(), bus::text(header.source()), payload)) {
    ++resume_checked_;
  } else if (++resume_mismatches_ <= 5) {
    spdlog::warn("{}: resuming: {} of {} at step {} differs from the recording", name(), topic,
                 bus::text(header.source()), header.step());
  }
  return true;
}

template <class Def>
std::unique_ptr<bus::Reader<Def>> RecorderNode::recordAsItComes(
    bus::Bus& bus, const Def& def, typename bus::Reader<Def>::LivelinessCallback on_liveliness) {
  return std::make_unique<bus::Reader<Def>>(
      bus, def,
      [this, topic = std::string(def.name)](const typename Def::Type& sample) {
        const auto payload = bus::serialize<Def>(sample);
        store(topic, sample.header(), payload);
        feed(topic, sample.header(), payload, true);
      },
      std::move(on_liveliness));
}

void RecorderNode::feed(const std::string& topic, const msg::SampleHeader& header,
                        const std::vector<std::uint8_t>& payload, bool now) {
  if (!feedWatched()) return;
  live_feed_->sample(topic, header.sim_time_ns(), payload.data(), payload.size());
  if (now) live_feed_->flushUnlessRecent(kFeedQuiet);
}

void RecorderNode::store(const std::string& topic, const msg::SampleHeader& header,
                         const std::vector<std::uint8_t>& payload) {
  std::lock_guard lock(recording_mutex_);
  if (recordedAlready(topic, header, payload)) return;
  recording_.insert(topic, header.step(), bus::text(header.source()), header.sim_time_ns(),
                    payload);
}

template <class Def>
void RecorderNode::record(const Def& def) {
  // Samples are stored as they arrive; in lockstep the input's wait for step
  // k then guarantees they are all in before StepDone(k).
  addTap(def, [this, topic = std::string(def.name)](const typename Def::Type& sample) {
    const bool kept = recorded(sample.header().step());
    if (!kept && !feedWatched()) return;
    thread_local std::vector<std::uint8_t> payload;  // its capacity stays: no allocation per sample
    bus::serializeInto<Def>(sample, payload);
    if (kept) store(topic, sample.header(), payload);
    feed(topic, sample.header(), payload, false);  // every step, decimated or not; sent with the step
  });
  producer_dividers_[std::string(def.name)] = dividerOf(std::string(def.producer));
}

void RecorderNode::recordDeliveries(const bus::StepContext& ctx) {
  for (const auto& [topic, plan] : bus_faults_.faulted()) {
    const auto divider = producer_dividers_.find(topic);
    if (divider == producer_dividers_.end()) continue;  // its producer is not in this rig
    const std::uint64_t due = ctx.step - ctx.step % divider->second;
    const auto held = plan->visibleStamp(ctx.step, divider->second);
    if (!plan->actsAt(due) && held == due) continue;
    msg::BusDelivery row;
    bus::stamp(row.header(), ctx, name());
    bus::setText(row.topic(), topic);
    row.sample_step(held ? static_cast<std::int64_t>(*held) : -1);
    row.dropped(plan->dropped(due));
    row.delay_steps(static_cast<std::uint32_t>(plan->delaySteps(due)));
    row.duplicated(plan->duplicated(due));
    store(std::string(bus::topics::kBusDelivery.name), row.header(),
          bus::serialize<std::remove_cvref_t<decltype(bus::topics::kBusDelivery)>>(row));
  }
}

RecorderNode::~RecorderNode() {
  try {
    storeIntruders();  // a lockstep run an intruder ended never reaches another step()
  } catch (const std::exception& e) {
    spdlog::error("{}: the intruders' fault events were not kept: {}", name(), e.what());
  }
  if (feedWatched()) {
    live_feed_->end();
    if (const auto dropped = live_feed_->framesDropped(); dropped > 0) {
      spdlog::warn("{}: the live feed's watchers missed {} frames (they did not keep up)", name(), dropped);
    }
  }
}

void RecorderNode::storeIntruders() {
  for (const auto& intruder : intrudersFrom(intruders_stored_)) {
    msg::FaultEvent event;
    const std::int64_t period_ns = options_.period.count();
    bus::stamp(event.header(), {intruder.step, static_cast<std::int64_t>(intruder.step) * period_ns, period_ns},
               intruder.participant.empty() ? std::string("?") : intruder.participant);
    bus::setText(event.kind(), "intruder");
    bus::setText(event.topic(), intruder.topic);
    bus::setText(event.writer(), intruder.writer);
    event.channel(-1);
    event.active(true);
    store(std::string(bus::topics::kFaultEvent.name), event.header(),
          bus::serialize<std::remove_cvref_t<decltype(bus::topics::kFaultEvent)>>(event));
    ++intruders_stored_;
  }
}

void RecorderNode::step(const bus::StepContext& ctx) {
  if (feedWatched()) live_feed_->flush();  // the step's samples, one send per watcher
  storeIntruders();
  if (recorded(ctx.step)) recordDeliveries(ctx);
  if ((ctx.step + 1) % params_.commit_every_steps != 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_commit_ < kCommitAtMostEvery) return;
  last_commit_ = now;
  std::lock_guard lock(recording_mutex_);
  // Lockstep, the samples of the next steps may be in already (the time
  // master lets the recorder trail: bus/StepReports.hpp); they
  // wait for the commit of their own steps. Paced, samples come as they come
  // (a bridge's older stamps after newer ones): a commit takes them all, in
  // the order they came.
  if (paced()) {
    recording_.commitInBackground();
  } else {
    recording_.commitInBackgroundThrough(ctx.step);
  }
}

void RecorderNode::beforeStopped() {
  storeIntruders();
  std::lock_guard lock(recording_mutex_);
  if (resume_after_) {
    recording_.setMeta(bus::meta::kResumeMismatches, std::to_string(resume_mismatches_));
    spdlog::info("{}: resumed after step {}: {} samples of the steps before matched the recording, {} did not",
                 name(), *resume_after_, resume_checked_, resume_mismatches_);
  }
  recording_.commit();  // every row stored: the figures have seen them all
  if (!figures_failure_.empty()) {
    spdlog::warn("{}: the summary's figures stopped ({}); the summary reads them from the recording", name(),
                 figures_failure_);
  }
  // For a launcher on another host, which summarises as this recorder stops;
  // kept again as the recording closes, with the rig's last health.
  if (const std::string figures = figuresJson(); !figures.empty() && recording_.storedEverySample()) {
    recording_.setMeta(bus::meta::kFigures, figures);
  }
  recording_.keepDigest();
  recording_.commit();
}

std::string RecorderNode::figuresJson() const {
  return figures_failure_.empty() && params_.figures ? params_.figures->json() : std::string();
}

RecorderParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                          bus::ConfigProblems& problems) {
  RecorderParams p;
  if (!args.out_dir.empty()) {
    p.path = (std::filesystem::path(args.out_dir) / "recording.sqlite").string();
  }
  auto r = scenario.componentParams(args.name, problems);
  r.read("record_every_steps", p.record_every_steps);
  // A transaction holds 50 recorded steps unless the scenario says otherwise:
  // each commit rewrites the pages it touched into the WAL, so committing
  // every 50 steps of a recording decimated to 1 in 10 wrote each page five
  // times as often (a one-orbit run: 25,757 pwrite calls).
  if (!r.has("commit_every_steps")) {
    p.commit_every_steps = static_cast<std::uint32_t>(
        std::min<std::uint64_t>(100000, std::uint64_t{p.commit_every_steps} * std::max(1u, p.record_every_steps)));
  }
  r.read("commit_every_steps", p.commit_every_steps);
  r.problems(p.validate());
  if (scenario.schedule().at(args.name) != 1) r.problem("rate_divider", "the recorder must run every step (1)");
  r.finish();
  // A scenario the other components refuse has no run to summarise.
  if (problems.empty()) {
    try {
      p.figures = makeSampleFigures(scenario);
    } catch (const std::exception& e) {
      spdlog::warn("recorder: no summary figures while recording ({}); the summary reads them back", e.what());
    }
  }
  p.meta = {{bus::meta::kScenario, scenario.name},
            {bus::meta::kSchedule, bus::meta::formatSchedule(scenario.schedule())},
            {bus::meta::kMode, scenario.pacing == bus::Pacing::kPaced ? "paced" : "lockstep"},
            {bus::meta::kLeaseMs, std::to_string(std::llround(scenario.liveliness_lease_s * 1e3))}};
  if (p.record_every_steps != 1) p.meta[bus::meta::kRecordEverySteps] = std::to_string(p.record_every_steps);
  return p;
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<RecorderNode>(argc, argv, "recorder", readParams);
}

}  // namespace flatsat::recorder
