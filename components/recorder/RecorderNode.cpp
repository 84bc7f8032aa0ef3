// SPDX-License-Identifier: Apache-2.0
#include "components/recorder/RecorderNode.hpp"

#include <filesystem>

#include "bus/Serialization.hpp"

namespace flatsat::recorder {

std::vector<std::string> RecorderParams::validate() const {
  std::vector<std::string> problems;
  if (path.empty()) problems.push_back("path: no recording file (give --out)");
  if (commit_every_steps < 1 || commit_every_steps > 100000) {
    problems.push_back("commit_every_steps: must be in 1..100000");
  }
  return problems;
}

RecorderNode::RecorderNode(bus::Bus& bus, bus::NodeOptions options, const RecorderParams& params)
    : Component(bus, std::move(options)),
      params_(params),
      recording_(params.path, bus::Recording::Access::kCreate) {
  bus::forEachTopic([this](const auto& def) {
    // Stepped topics whose producer runs in this rig; the protocol topics
    // (grant, done) are bookkeeping, not data.
    if (def.qos == bus::QosKind::kStepped && !def.producer.empty() &&
        def.name != bus::topics::kStepGrant.name &&
        options_.schedule.count(std::string(def.producer))) {
      record(def);
    }
  });
  health_ = std::make_unique<bus::ReaderOf<bus::topics::kHealth>>(
      bus, bus::topics::kHealth, [this](const msg::Health& health) {
        std::lock_guard lock(recording_mutex_);
        recording_.insert(std::string(bus::topics::kHealth.name), health.header().step(),
                          bus::text(health.header().source()), 0,
                          bus::serialize<std::remove_cvref_t<decltype(bus::topics::kHealth)>>(health));
      });
}

template <class Def>
void RecorderNode::record(const Def& def) {
  auto& input = addInput(def);
  const std::uint32_t divider = dividerOf(std::string(def.producer));
  store_.push_back([this, &input, divider, topic = std::string(def.name)](std::uint64_t k) {
    if (k % divider != 0) return;
    const auto sample = input.at(k);
    recording_.insert(topic, k, bus::text(sample.header().source()),
                      sample.header().sim_time_ns(), bus::serialize<Def>(sample));
  });
}

void RecorderNode::step(const bus::StepContext& ctx) {
  std::lock_guard lock(recording_mutex_);
  for (const auto& store : store_) store(ctx.step);
  if ((ctx.step + 1) % params_.commit_every_steps == 0) recording_.commit();
}

RecorderParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                          bus::ConfigProblems& problems) {
  RecorderParams p;
  if (!args.out_dir.empty()) {
    p.path = (std::filesystem::path(args.out_dir) / "recording.sqlite").string();
  }
  auto r = scenario.componentParams(args.name, problems);
  r.read("commit_every_steps", p.commit_every_steps);
  r.problems(p.validate());
  if (scenario.schedule().at(args.name) != 1) r.problem("rate_divider", "the recorder must run every step (1)");
  r.finish();
  return p;
}

}  // namespace flatsat::recorder
