// SPDX-License-Identifier: Apache-2.0
#include "bus/TimeMaster.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>

#include <algorithm>
#include <cstring>
#include <string_view>

#include <spdlog/spdlog.h>

namespace flatsat::bus {

TimeMaster::TimeMaster(Bus& bus, NodeOptions options, Timing timing)
    : Node(bus, std::move(options)),
      timing_(timing),
      done_reader_(bus, topics::kStepDone,
                   [this](const msg::StepDone& done) {
                     {
                       const auto& source = done.header().source();
                       const std::string_view from(source.data(), ::strnlen(source.data(), source.size()));
                       const auto lock = lockIfThreaded();
                       for (Awaited& a : awaited_) {
                         if (a.component != from) continue;
                         a.newest_done = std::max(a.newest_done.value_or(0), done.header().step());
                         break;
                       }
                     }
                     notify();
                   },
                   {}, {}, trustBySource(topics::kStepDone)),
      health_reader_(bus, topics::kHealth,
                     [this](const msg::Health& health) {
                       {
                         std::lock_guard lock(mutex_);
                         const auto source = text(health.header().source());
                         states_[source] = health.state();
                         messages_[source] = text(health.message());
                         health_arrived_[source] = std::chrono::steady_clock::now();
                         if (late_.erase(source) > 0) {
                           spdlog::info("{}: {} is on time again", name(), source);
                           component_events_.push_back({source, "late", false});
                         }
                         // A lost component starting again (restarted): its new writer is alive.
                         if ((health.state() == msg::ComponentState::STARTING ||
                              health.state() == msg::ComponentState::READY) &&
                             lost_.erase(source) > 0) {
                           spdlog::info("{}: {} is back", name(), source);
                           component_events_.push_back({source, "lost", false});
                         }
                       }
                       changed_.notify_all();
                     },
                     [this](const std::string& source, bool alive) { livelinessChanged(source, alive); },
                     {}, trustBySource(topics::kHealth)),
      grant_(bus, topics::kStepGrant),
      bus_fault_events_(bus, topics::kFaultEvent),
      bus_fault_acks_(bus) {
  if (timing.period_ns <= 0) throw NodeFailure(name() + ": step period must be > 0");
  {
    std::lock_guard lock(mutex_);  // the StepDone reader exists already
    for (const auto& [component, divider] : options_.schedule) {
      if (component == name()) continue;
      awaited_.push_back({component, {divider, timing_.final_step}, std::nullopt});
    }
  }
  acknowledgeBusFaults(bus_fault_acks_);
}

bool TimeMaster::ended(const std::string& component) const {
  const auto state = states_.find(component);
  return state != states_.end() &&
         (state->second == msg::ComponentState::STOPPED || state->second == msg::ComponentState::FAILED);
}

std::string TimeMaster::failedComponents() const {
  std::string failed;
  for (const auto& [component, state] : states_) {
    if (state == msg::ComponentState::FAILED) {
      failed += " " + component + " (" + messages_.at(component) + ")";
    } else if (lost_.count(component) != 0) {
      failed += " " + component + " (no liveliness for " + std::to_string(kHealthLease.count()) +
                " ms: its process is gone)";
    }
  }
  return failed;
}

void TimeMaster::livelinessChanged(const std::string& component, bool alive) {
  {
    std::lock_guard lock(mutex_);
    if (component == name() || (!alive && ended(component))) return;
    if (std::find(options_.externals.begin(), options_.externals.end(), component) == options_.externals.end()) {
      // The launcher started its process and watches it: a death it sees at
      // once. A lease that lapsed with the process alive is a starved process
      // (a loaded machine, a debugger): late, not gone; lockstep waits for it
      // up to the step timeout, as for any slow step.
      if (alive ? late_.erase(component) == 0 : !late_.insert(component).second) return;
      if (alive) {
        spdlog::info("{}: {} is on time again (its liveliness is back)", name(), component);
      } else {
        spdlog::warn("{}: {} is late: no sign of life for {} ms; its process is the launcher's to watch", name(),
                     component, kHealthLease.count());
      }
      component_events_.push_back({component, "late", !alive});
    } else if (alive == (lost_.count(component) == 0)) {
      return;
    } else {
      if (alive) {
        lost_.erase(component);
        spdlog::info("{}: {} is alive again", name(), component);
      } else {
        lost_.insert(component);
        late_.erase(component);  // gone, not late
        spdlog::warn("{}: {} lost its liveliness ({} ms without a sign of life)", name(), component,
                     kHealthLease.count());
      }
      component_events_.push_back({component, "lost", !alive});
    }
  }
  changed_.notify_all();
}

void TimeMaster::waitForComponents() {
  waitUntilNothingMissing(
      [this] {
        std::lock_guard lock(mutex_);
        if (auto failed = failedComponents(); !failed.empty()) {
          throw NodeFailure(name() + ": component failed before the start:" + failed);
        }
        std::string missing;
        for (const auto& [component, divider] : options_.schedule) {
          if (component == name()) continue;
          auto it = states_.find(component);
          if (it == states_.end() || it->second != msg::ComponentState::READY) {
            missing += " " + component;
          }
        }
        return missing;
      },
      "waiting for every component to be READY");
}

void TimeMaster::resendStep(std::uint64_t k, const std::string& missing) {
  spdlog::warn("{}: step {} stalled for {} s, granting it again; waiting for:{}", name(), k,
               std::chrono::duration_cast<std::chrono::seconds>(kResendAfter).count(), missing);
  rewriteOutputs();
  writeGrant(k);
}

void TimeMaster::writeGrant(std::uint64_t k, bool stop) {
  msg::StepGrant grant;
  stamp(grant.header(), context(k), name());
  grant.step_period_ns(timing_.period_ns);
  grant.final_step(timing_.final_step);
  grant.stop(stop);
  grant_.write(grant);
}

bool TimeMaster::Awaited::doneWith(std::uint64_t k) const {
  const std::uint64_t needed = reports.neededToClose(k);
  return !reports.reportsAt(needed) || (newest_done && *newest_done >= needed);
}

std::string TimeMaster::notDone(std::uint64_t k) const {
  std::string missing;
  for (const Awaited& a : awaited_) {
    if (!a.doneWith(k)) missing += " " + a.component;
  }
  return missing;
}

bool TimeMaster::allDone(std::uint64_t k) const {
  return std::all_of(awaited_.begin(), awaited_.end(), [k](const Awaited& a) { return a.doneWith(k); });
}

void TimeMaster::waitForDone(std::uint64_t k) {
  {
    std::lock_guard lock(mutex_);
    if (allDone(k)) return;  // the usual case composed, without a clock read
  }
  const auto deadline = std::chrono::steady_clock::now() + options_.step_timeout;
  auto next_resend = std::chrono::steady_clock::now() + kResendAfter;
  std::unique_lock lock(mutex_);
  // Its inputs are waited for next: woken once both are in.
  const WakeWhen wake(*this, lock, [this, k] { return allDone(k) && inputsIn(k); });
  for (;;) {
    const std::string missing = notDone(k);
    if (missing.empty()) return;
    throwIfFatal();
    if (auto failed = failedComponents(); !failed.empty()) {
      throw NodeFailure(name() + ": step " + std::to_string(k) + ": component failed:" + failed);
    }
    if (interrupted()) throw NodeFailure(name() + ": interrupted at step " + std::to_string(k));
    if (std::chrono::steady_clock::now() > deadline) {
      throw NodeFailure(name() + ": step " + std::to_string(k) + ": no StepDone within " +
                        std::to_string(options_.step_timeout.count()) + " ms from:" + missing);
    }
    if (std::chrono::steady_clock::now() > next_resend) {
      next_resend += kResendAfter;
      lock.unlock();  // publishing: never under the node's lock
      resendStep(k, missing);
      lock.lock();
      continue;
    }
    changed_.wait_for(lock, std::chrono::milliseconds(100));
  }
}

void TimeMaster::waitForTick(std::chrono::steady_clock::time_point tick) {
  std::unique_lock lock(mutex_);
  // Sleep to kTickSpin before the tick, then spin: a sleeping thread wakes
  // up to the timer slack plus the scheduler's latency late, which on a
  // loaded 2-vCPU guest was 2 ms at the 99th percentile (the paced rig's
  // target is 200 µs). The spin costs kTickSpin of one core per period.
  while (std::chrono::steady_clock::now() < tick - kTickSpin) {
    if (interrupted()) throw NodeFailure(name() + ": interrupted");
    changed_.wait_until(lock, tick - kTickSpin);
  }
  lock.unlock();
  while (std::chrono::steady_clock::now() < tick) {
  }
  lock.lock();
  // Paced steps wait for nobody; who was late shows in their health.
  findLate(tick);
}

void TimeMaster::findLate(std::chrono::steady_clock::time_point now) {
  for (const auto& [component, arrived] : health_arrived_) {
    const auto state = states_.find(component);
    // Health comes with a grant the component is due for: every kHealthPeriod, or
    // every divider periods when that is longer.
    const auto divider = options_.schedule.count(component) != 0 ? options_.schedule.at(component) : 1U;
    const auto late_after = std::max<std::chrono::nanoseconds>(
        kHealthLate, std::chrono::duration_cast<std::chrono::nanoseconds>(kHealthPeriod + 1.5 * divider * options_.period));
    if (component == name() || now - arrived <= late_after || late_.count(component) != 0 ||
        lost_.count(component) != 0 || state == states_.end() || state->second != msg::ComponentState::RUNNING) {
      continue;
    }
    late_.insert(component);
    spdlog::warn("{}: {} is late: no health for {} ms (its steps are not turning)", name(), component,
                 std::chrono::duration_cast<std::chrono::milliseconds>(now - arrived).count());
    component_events_.push_back({component, "late", true});
  }
}

void TimeMaster::run() {
  try {
    start();
    for (std::uint64_t k = 0; k <= timing_.final_step; ++k) {
      beginStep(k);
      endStep(k);
    }
    stop();
  } catch (const NodeFailure& failure) {
    publishLastHealth(msg::ComponentState::FAILED, 0, failure.what());
    throw;
  }
}

void TimeMaster::keepTime() const {
  ::prctl(PR_SET_TIMERSLACK, 1UL);  // this thread's sleeps end on time, not up to 50 µs late
  // Real-time priority, where the process may take it: a woken master then
  // runs at once instead of waiting for the components it is about to
  // grant a step to. It sleeps most of each period, and the kernel's RT
  // throttling keeps a share for everything else in any case.
  sched_param param{};
  param.sched_priority = 10;
  if (::pthread_setschedparam(::pthread_self(), SCHED_FIFO, &param) != 0) {
    spdlog::info("{}: no real-time priority for the ticks (not permitted here); they may come later", name());
  }
}

void TimeMaster::start() {
  waitForProducers();
  waitForComponents();
  publishHealth(msg::ComponentState::RUNNING, 0, "granting steps");
  spdlog::info("{}: every component ready; running steps 0..{} {}", name(), timing_.final_step,
               paced() ? "paced on the wall clock" : "in lockstep");
  if (paced()) keepTime();
  start_ = std::chrono::steady_clock::now();
  next_health_ = start_ + kHealthPeriod;
}

void TimeMaster::publishFaultEvents(const StepContext& ctx) {
  bus_fault_acks_.publish(ctx, name());
  std::vector<ComponentEvent> component_events;
  {
    std::lock_guard lock(mutex_);
    component_events.swap(component_events_);
  }
  for (const auto& [component, kind, active] : component_events) {
    msg::FaultEvent event;
    stamp(event.header(), ctx, component);
    setText(event.kind(), kind);
    setText(event.topic(), topics::kHealth.name);
    event.channel(-1);
    event.active(active);
    bus_fault_events_.write(event);
  }
  for (const auto& [topic, plan] : bus_faults_.faulted()) {
    const auto faults = plan->faults();
    for (std::size_t i = 0; i < faults.size(); ++i) {
      const bool now = faults[i].actsAt(ctx.sim_time_ns);
      bool& before = bus_fault_active_[{topic, i}];
      if (now == before) continue;
      before = now;
      msg::FaultEvent event;
      stamp(event.header(), ctx, std::string(kBusFaultTarget));
      setText(event.kind(), toString(faults[i].kind));
      setText(event.topic(), topic);
      event.channel(-1);
      event.magnitude(faults[i].magnitude);
      event.active(now);
      bus_fault_events_.write(event);
    }
  }
}

void TimeMaster::beginStep(std::uint64_t k) {
  if (paced()) {
    tick_lateness_.add(std::chrono::steady_clock::now() - (start_ + std::chrono::nanoseconds(timing_.period_ns) * k));
  }
  const StepContext ctx = context(k);
  granted(k);
  publishFaultEvents(ctx);
  publishStep(ctx);
  // Implied grants: the components take step k from their inputs of k, which
  // come once k - 1 is closed; the first grant tells them the run's timing.
  if (!options_.implied_grants || k == 0) writeGrant(k);
  if (heartbeat_closed_) {
    publishHealth(msg::ComponentState::RUNNING, *heartbeat_closed_ + 1, "granting steps");
    heartbeat_closed_.reset();
  }
}

void TimeMaster::endStep(std::uint64_t k) {
  if (paced()) {
    waitForTick(start_ + std::chrono::nanoseconds(timing_.period_ns) * (k + 1));
  } else {
    waitForDone(k);
    waitForInputs(k);
  }
  advance(context(k));
  dropInputsAfter(k);
  reachedStep(k);
  if (k >= timing_.final_step) lastStepReached();
  // Heartbeat (counts stay current) of step k's close, written after the
  // next grant, never between a tick and it: paced at 100 Hz, the one step
  // in a hundred that carried it was granted 220 to 620 µs late, the 99th
  // percentile's whole excess. Lockstep reads the clock every 16th step, as
  // Component::handle.
  if ((paced() || k % 16 == 0) && std::chrono::steady_clock::now() > next_health_) {
    heartbeat_closed_ = k;
    next_health_ += kHealthPeriod;
  }
}

void TimeMaster::addToHealth(msg::Health& health) const {
  if (heartbeat_closed_) {  // as the step stood when it closed: nothing granted after it yet
    health.step_reached(*heartbeat_closed_);
    health.step_granted(*heartbeat_closed_);
  }
  if (!paced()) return;
  health.tick_late_us_p50(static_cast<float>(tick_lateness_.quantileUs(0.50)));
  health.tick_late_us_p99(static_cast<float>(tick_lateness_.quantileUs(0.99)));
  health.tick_late_us_max(static_cast<float>(tick_lateness_.maxUs()));
}

void TimeMaster::stop() {
  heartbeat_closed_.reset();  // the last health tells the run's end
  writeGrant(timing_.final_step + 1, true);
  flushOutputs();
  grant_.waitForAcknowledgments(std::chrono::seconds(5));
  publishLastHealth(msg::ComponentState::STOPPED, timing_.final_step + 1, "run complete");
  if (!inProcess()) waitForStoppedComponents(std::chrono::seconds(5));
}

void TimeMaster::waitForStoppedComponents(std::chrono::seconds timeout) {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, timeout, [this] {
    return std::all_of(awaited_.begin(), awaited_.end(),
                       [this](const Awaited& a) { return lost_.count(a.component) != 0 || ended(a.component); });
  });
}

}  // namespace flatsat::bus
