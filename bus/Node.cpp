// SPDX-License-Identifier: Apache-2.0
#include "bus/Node.hpp"

#include <chrono>

#include <spdlog/spdlog.h>

#include "bus/Shutdown.hpp"

namespace flatsat::bus {

namespace {
constexpr auto kPoll = std::chrono::milliseconds(100);  // shutdown-flag polling period
}

Node::Node(Bus& bus, NodeOptions options)
    : bus_(bus),
      options_(std::move(options)),
      health_(bus, topics::kHealth),
      // In process (composed) there is no liveliness to assert: no thread.
      liveliness_(bus.localHub() != nullptr ? std::jthread() : std::jthread([this](std::stop_token stop) {
        std::mutex mutex;
        std::condition_variable_any wake;
        std::unique_lock lock(mutex);
        while (!stop.stop_requested()) {
          health_.assertLiveliness();
          // Six times a lease: a process the scheduler holds back for a while
          // (a loaded machine, a debugger's short stop) stays alive.
          wake.wait_for(lock, stop, kHealthLease / 6, [] { return false; });
        }
      })),
      bus_faults_(options_.seed, std::chrono::nanoseconds(options_.period).count(), options_.bus_faults),
      bus_fault_commands_(bus, topics::kFaultCmd, [this](const msg::FaultCmd& command) {
        if (text(command.target()) != kBusFaultTarget) return;
        BusFault fault;
        const auto problems = busFaultFromCommand(command, fault);
        if (problems.empty()) bus_faults_.add(fault);
        if (CommandAcks* acks = bus_fault_acks_.load()) {
          acks->queue(command.command_id(), "fault", problems.empty(),
                      problems.empty() ? std::string(toString(fault.kind)) + " on " + fault.topic + " added"
                                       : problems.front());
        }
      }) {
  publishHealth(msg::ComponentState::STARTING, 0, "entities created");
}

std::vector<std::string> busFaultFromCommand(const msg::FaultCmd& command, BusFault& fault) {
  std::vector<std::string> problems;
  const std::string kind = text(command.kind());
  if (!parseBusFaultKind(kind, fault.kind)) {
    problems.push_back("kind: '" + kind + "' is not one of " + kBusFaultKinds);
  }
  fault.topic = text(command.topic());
  if (!isSteppedTopic(fault.topic)) problems.push_back("topic: '" + fault.topic + "' is not a stepped topic");
  fault.magnitude = command.magnitude();
  fault.start_ns = command.start_ns();
  fault.duration_ns = command.duration_ns();
  for (auto& p : fault.validate()) problems.push_back(std::move(p));
  return problems;
}

Node::~Node() = default;

std::uint32_t Node::dividerOf(const std::string& component) const {
  auto it = options_.schedule.find(component);
  if (it == options_.schedule.end()) {
    throw NodeFailure(options_.name + ": needs input from '" + component +
                      "', which is not in the rig's schedule");
  }
  return it->second;
}

bool Node::interrupted() { return shutdownRequested(); }

void Node::waitForProducers() {
  waitUntilNothingMissing(
      [this] {
        std::string missing;
        for (const auto& input : inputs_) {
          if (!input->producerMatched()) missing += " " + input->topicName();
        }
        return missing;
      },
      "waiting for producers to match");
}

void Node::notify() {
  // In process (a composed rig) the samples arrive on the one thread that
  // would wait: nobody can be waiting, and the lock and wake-up were a fifth
  // of the bookkeeping of a composed step (callgrind).
  if (inProcess()) return;
  // Taking the lock orders the change before a waiter's check, so no
  // wake-up is lost between its check and its wait.
  {
    std::lock_guard lock(mutex_);
    if (wake_when_ && !wake_when_()) return;
  }
  changed_.notify_all();
}

bool Node::inputsIn(std::uint64_t k) const {
  for (const auto& input : inputs_) {
    if (!input->has(k)) return false;
  }
  return true;
}

bool Node::waitForInputs(std::uint64_t k) {
  {
    std::lock_guard lock(mutex_);
    if (inputsIn(k)) return true;  // the usual case, without a clock read
  }
  const auto now = std::chrono::steady_clock::now();
  const auto deadline = now + (paced() ? std::chrono::duration_cast<std::chrono::milliseconds>(
                                              options_.period / 2)
                                       : options_.step_timeout);
  auto next_resend = now + kResendAfter;
  std::unique_lock lock(mutex_);
  const WakeWhen wake(*this, lock, [this, k] { return inputsIn(k); });
  for (;;) {
    const InputBase* missing = nullptr;
    for (const auto& input : inputs_) {
      if (!input->has(k)) {
        missing = input.get();
        break;
      }
    }
    if (missing == nullptr) return true;
    throwIfFatal();
    if (interrupted()) {
      throw NodeFailure(options_.name + ": interrupted at step " + std::to_string(k));
    }
    if (std::chrono::steady_clock::now() > deadline) {
      if (!paced()) {
        throw NodeFailure(options_.name + ": step " + std::to_string(k) + ": no sample on " +
                          missing->topicName() + " within " +
                          std::to_string(options_.step_timeout.count()) + " ms");
      }
      ++stale_inputs_;
      for (const auto& input : inputs_) {
        if (!input->hasAny(k)) return false;
      }
      return true;
    }
    if (!paced() && std::chrono::steady_clock::now() > next_resend) {
      next_resend += kResendAfter;
      lock.unlock();  // onStall publishes: never under the node's lock
      onStall(k);
      lock.lock();
      continue;
    }
    changed_.wait_until(lock, std::min(deadline, std::chrono::steady_clock::now() + kPoll));
  }
}

void Node::dropInputsAfter(std::uint64_t k) {
  // Lockstep, an input then holds nothing between steps when its producer
  // steps every step, and the next sample lands in the empty slot. Dropped
  // before k only, the sample of k stayed until the one of k + 1 came and was
  // then moved down behind it: a kilobyte truth, five times a step
  // (callgrind).
  const std::uint64_t unused_before = paced() ? k : k + 1;
  for (auto& input : inputs_) input->dropBefore(unused_before);
}

void Node::rewriteOutputs() {
  for (auto& output : outputs_) output->rewrite();
}

void Node::flushOutputs() {
  for (auto& output : outputs_) {
    if (!output->flush()) spdlog::warn("{}: an output was not acknowledged by every reader", name());
  }
}

void Node::publishHealth(msg::ComponentState state, std::uint64_t steps_done,
                         const std::string& message) {
  msg::Health health;
  setText(health.header().source(), options_.name);
  health.header().step(steps_done);
  health.state(state);
  health.steps_done(steps_done);
  health.stale_inputs(stale_inputs_);
  health.overruns(overruns_);
  health.samples_dropped(bus_.samplesDropped());
  health.commands_refused(bus_.commandsRefused());
  health.wall_time_ns(static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(
          std::chrono::system_clock::now().time_since_epoch())
          .count()));
  setText(health.message(), message);
  health.step_reached(step_reached_);
  health.step_granted(std::max(newestGrant(), step_reached_));
  std::uint64_t copies = 0;
  for (const auto& input : inputs_) copies += input->copiesDropped();
  health.copies_dropped(copies);
  health.deadlines_missed(deadlines_missed_.load());
  {
    std::lock_guard lock(refused_mutex_);
    health.samples_rejected(refused_total_);
    std::size_t slot = 0;
    for (const auto& [topic, count] : refused_) {
      if (slot == health.rejected_by_topic().size()) break;
      setText(health.rejected_by_topic()[slot].topic(), topic);
      health.rejected_by_topic()[slot++].count(count);
    }
    health.intruders(intruders_.size());
  }
  health.commands_clamped(commands_clamped_.load());
  addToHealth(health);
  health_.write(health);
}

void Node::inputLate(const std::string& topic, const std::string& producer) {
  if (last_step_reached_.load(std::memory_order_relaxed)) return;
  const std::uint64_t missed = ++deadlines_missed_;
  spdlog::warn("{}: {} from {} is late: nothing within its deadline; {} deadline(s) missed so far", name(), topic,
               producer.empty() ? "its producer" : producer, missed);
}

void Node::refuseSample(const std::string& topic, const msg::SampleHeader& header, Breach why, bool as_missing) {
  std::uint64_t n = 0;
  {
    std::lock_guard lock(refused_mutex_);
    ++refused_total_;
    n = ++refused_[topic];
  }
  std::uint64_t decade = 1;  // a flood of bad samples does not flood the log
  while (decade <= n / 10) decade *= 10;
  if (n == decade) {
    spdlog::warn("{}: refused a sample on {} from '{}' stamped step {}: {} {}; {} ({} refused on it so far)", name(),
                 topic, text(header.source()), header.step(), why.field, why.reason,
                 as_missing ? "taken as missing" : "dropped", n);
  }
}

void Node::foreignWriter(const std::string& topic, const std::string& expected, bool fatal, const std::string& guid,
                         const std::string& participant, bool first, bool sample) {
  {
    std::lock_guard lock(refused_mutex_);
    if (sample) {
      ++refused_total_;
      ++refused_[topic];
    }
    if (first) intruders_.push_back({topic, guid, participant, newestGrant()});
  }
  if (!first) return;
  // The participant first: a health message keeps 95 characters of the reason.
  const std::string who = "participant '" + participant + "' (writer " + guid + ")";
  spdlog::error("{}: intruder on {}: {} is not its producer '{}'; its samples are ignored", name(), topic, who,
                expected);
  if (!fatal) return;
  {
    std::lock_guard lock(mutex_);
    if (!fatal_set_) {
      fatal_set_ = true;
      fatal_ = name() + ": intruder on " + topic + ": " + who + ", not its producer '" + expected +
               "': a lockstep run cannot go on, as exclusive ownership may give the readers its samples "
               "in place of the producer's";
    }
  }
  changed_.notify_all();
}

std::vector<Node::Intruder> Node::intrudersFrom(std::size_t from) const {
  std::lock_guard lock(refused_mutex_);
  if (from >= intruders_.size()) return {};
  return {intruders_.begin() + static_cast<std::ptrdiff_t>(from), intruders_.end()};
}

void Node::publishLastHealth(msg::ComponentState state, std::uint64_t steps_done,
                             const std::string& message) {
  publishHealth(state, steps_done, message);
  if (!health_.waitForAcknowledgments(std::chrono::seconds(2))) {
    spdlog::warn("{}: not every reader acknowledged the last health", name());
  }
}

}  // namespace flatsat::bus
