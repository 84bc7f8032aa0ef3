// SPDX-License-Identifier: Apache-2.0
#include "bus/Component.hpp"

#include <spdlog/spdlog.h>

namespace flatsat::bus {

Component::Component(Bus& bus, NodeOptions options)
    : Node(bus, std::move(options)),
      grant_reader_(bus, topics::kStepGrant,
                    [this](const msg::StepGrant& grant) {
                      granted(grant.header().step());
                      {
                        const auto lock = lockIfThreaded();
                        if (options_.implied_grants && !grant.stop()) {
                          // Ahead of the steps this component granted itself: a resend it
                          // needs not (its inputs of that step are not in, or it would be there).
                          if (granted_itself_ && grant.header().step() > *granted_itself_) return;
                          implied_ = grant;
                          if (!granted_itself_) granted_itself_ = grant.header().step();
                        }
                        if (grant_observer_) grant_observer_(grant);
                        if (skip_through_ && grant.header().step() <= *skip_through_ && !grant.stop()) return;
                        grants_.push_back({grant.header().step(), grant.header().sim_time_ns(),
                                           grant.step_period_ns(), grant.final_step(), grant.stop()});
                      }
                      notify();
                    },
                    {}, {}, trustFor(topics::kStepGrant)),
      done_(bus, topics::kStepDone) {}

void Component::run() {
  try {
    start();
    loop();
    finish();
  } catch (const NodeFailure& failure) {
    publishLastHealth(msg::ComponentState::FAILED, steps_done_, failure.what());
    throw;
  }
}

void Component::restoreCheckpoint() {
  std::optional<Checkpoint> checkpoint;
  try {
    checkpoint = readCheckpoint(options_.checkpoint_file, name());
  } catch (const std::exception& e) {
    spdlog::error("{}: restarted, its checkpoint is unusable, starting afresh: {}", name(), e.what());
    return;
  }
  if (!checkpoint) {  // the process it replaces died before it claimed a step: none is on the bus
    spdlog::warn("{}: restarted, but {} holds no checkpoint: starting afresh", name(), options_.checkpoint_file);
    return;
  }
  skipGrantsThrough(checkpoint->claimed);
  if (checkpoint->state.is_null() || saveState().is_null()) {
    checkpoint_ = Checkpoint{checkpoint->step, nullptr, checkpoint->claimed};
    return;
  }
  try {
    restoreState(checkpoint->state);
    checkpoint_ = *checkpoint;
    spdlog::info("{}: restarted with the state it had after step {} ({})", name(), checkpoint->step,
                 options_.checkpoint_file);
  } catch (const std::exception& e) {
    spdlog::error("{}: restarted, the state in {} is unusable, starting afresh: {}", name(),
                  options_.checkpoint_file, e.what());
    checkpoint_ = Checkpoint{0, nullptr, checkpoint->claimed};
  }
}

void Component::skipGrantsThrough(std::uint64_t claimed) {
  std::lock_guard lock(mutex_);
  skip_through_ = claimed;
  // The grants' transient-local history may have come in already.
  std::erase_if(grants_, [claimed](const Grant& grant) { return !grant.stop && grant.step <= claimed; });
  spdlog::info("{}: restarted: steps only grants after step {}, the newest its earlier process began", name(),
               claimed);
}

void Component::keepCheckpoint() {
  try {
    writeCheckpoint(options_.checkpoint_file, name(), checkpoint_);
  } catch (const std::exception& e) {  // the run matters more than a later restart
    spdlog::error("{}: no more checkpoints: {}", name(), e.what());
    options_.checkpoint_file.clear();
  }
}

void Component::start() {
  if (options_.restarted && !options_.checkpoint_file.empty()) restoreCheckpoint();
  waitForProducers();
  waitUntilNothingMissing(
      [this] {
        return grant_reader_.matchedWriters() == 0 ? " " + grant_reader_.topicName() : std::string();
      },
      "waiting for the time master");
  divider_ = dividerOf(name());
  publishHealth(msg::ComponentState::READY, 0, "all producers matched");
  spdlog::info("{}: ready (divider {})", name(), divider_);
  next_health_ = std::chrono::steady_clock::now() + kHealthPeriod;
}

void Component::finish() {
  lastStepReached();  // a stop may come before the last step: an interrupted or skipped-ahead run
  flushOutputs();
  done_.waitForAcknowledgments(std::chrono::seconds(5));
  beforeStopped();
  publishLastHealth(msg::ComponentState::STOPPED, steps_done_, "run complete");
  spdlog::info("{}: stopped after {} steps", name(), steps_done_);
}

void Component::loop() {
  while (handle(nextGrant())) {
  }
}

Component::Turn Component::turn() {
  Grant grant;
  {
    const auto lock = lockIfThreaded();
    if (grants_.empty()) return Turn::kIdle;
    grant = grants_.front();
    if (!grant.stop && grant.step % divider_ == 0 && !inputsIn(grant.step)) return Turn::kBlocked;
    grants_.pop_front();
  }
  return handle(grant, true) ? Turn::kStepped : Turn::kStopped;
}

bool Component::handle(const Grant& grant, bool inputs_in) {
  if (grant.stop) return false;
  throwIfFatal();
  const StepContext ctx{grant.step, grant.sim_time_ns, grant.period_ns};
  if (granted_ && ctx.step <= *granted_) {  // granted again after a stall (kResendAfter)
    rewriteOutputs();
    done_.rewriteLast();
    return true;
  }
  granted_ = ctx.step;
  if (ctx.step % divider_ == 0 && (inputs_in || waitForInputs(ctx.step))) {
    // Claimed before any output of the step can reach the bus, so a process
    // killed mid-step is never followed by one that publishes the step again.
    if (!options_.checkpoint_file.empty()) {
      checkpoint_.claimed = ctx.step;
      keepCheckpoint();
    }
    step(ctx);
    if (StepReports{divider_, grant.final_step}.reportsAt(ctx.step)) {
      msg::StepDone done;
      stamp(done.header(), ctx, name());
      done_.write(done);
    }
    ++steps_done_;
    if (!options_.checkpoint_file.empty()) {
      if (auto state = saveState(); !state.is_null()) {
        checkpoint_.step = ctx.step;
        checkpoint_.state = std::move(state);
        keepCheckpoint();
      }
    }
  }
  dropInputsAfter(ctx.step);
  reachedStep(ctx.step);
  if (ctx.step >= grant.final_step) lastStepReached();
  if (options_.implied_grants && ctx.step < grant.final_step) grantItself(grant);
  // Lockstep looks at the clock every 16th step only: a heartbeat a few
  // steps late tells the same, and a composed rig steps faster than the
  // clock reads it took. Paced steps follow the clock anyway.
  if ((paced() || ++lockstep_grants_ % 16 == 0) && std::chrono::steady_clock::now() > next_health_) {
    publishHealth(msg::ComponentState::RUNNING, steps_done_, status_);
    next_health_ += kHealthPeriod;
  }
  return true;
}

void Component::grantItself(const Grant& after) {
  // The time master's grant of the next step, to the bit (TimeMaster::context):
  // the recorder keeps it as if it had come.
  const Grant next{after.step + 1, after.sim_time_ns + after.period_ns, after.period_ns, after.final_step, false};
  granted(next.step);
  const auto lock = lockIfThreaded();
  granted_itself_ = next.step;
  if (grant_observer_) {
    stamp(implied_.header(), {next.step, next.sim_time_ns, next.period_ns}, text(implied_.header().source()));
    grant_observer_(implied_);
  }
  grants_.push_back(next);
}

void Component::onStall(std::uint64_t /*k*/) {
  if (!options_.implied_grants || !granted_) return;
  rewriteOutputs();
  done_.rewriteLast();
}

void Component::observeGrants(std::function<void(const msg::StepGrant&)> observer) {
  const auto lock = lockIfThreaded();
  grant_observer_ = std::move(observer);
}

void Component::setStatus(const std::string& status) {
  if (status == status_) return;
  status_ = status;
  publishHealth(msg::ComponentState::RUNNING, steps_done_, status_);
}

Component::Grant Component::nextGrant() {
  const auto deadline = std::chrono::steady_clock::now() + options_.step_timeout;
  std::unique_lock lock(mutex_);
  // Woken once the work of a grant can be done: its inputs are in, or it is
  // the stop. Grants it is not due for wait for the next one it is: nobody
  // waits for those (a 1 Hz controller of a 10 Hz rig woke every step).
  const WakeWhen wake(*this, lock, [this] {
    for (const Grant& grant : grants_) {
      if (grant.stop) return true;
      if (grant.step % divider_ == 0) return inputsIn(grant.step);
    }
    return false;
  });
  while (grants_.empty()) {
    throwIfFatal();
    if (interrupted()) throw NodeFailure(name() + ": interrupted");
    if (std::chrono::steady_clock::now() > deadline) {
      throw NodeFailure(name() + ": no step grant from the time master for " +
                        std::to_string(options_.step_timeout.count()) + " ms");
    }
    changed_.wait_for(lock, std::chrono::milliseconds(100));
  }
  // Paced, a component that fell behind skips to the newest grant: the
  // wall clock does not wait, so old steps are not worth computing.
  while (paced() && grants_.size() > 1 && !grants_.front().stop) {
    grants_.pop_front();
    ++overruns_;
  }
  const Grant grant = grants_.front();
  grants_.pop_front();
  return grant;
}

}  // namespace flatsat::bus
