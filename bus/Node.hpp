// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <chrono>
#include <condition_variable>
#include <algorithm>
#include <atomic>
#include <functional>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <iterator>
#include <thread>
#include <vector>

#include "bus/Bus.hpp"
#include "bus/BusFaults.hpp"
#include "bus/CommandAcks.hpp"
#include "bus/Endpoints.hpp"
#include "bus/SampleChecks.hpp"
#include "bus/Stamp.hpp"
#include "bus/StepSamples.hpp"
#include "bus/Topics.hpp"

namespace flatsat::bus {

/// Step dividers of every scheduled component of the rig, by name: a
/// component due at k when k % divider == 0.
using Schedule = std::map<std::string, std::uint32_t>;

/// How simulated time advances (architecture, "Time and the step protocol").
enum class Pacing {
  kLockstep,  ///< every step waits for every due component: deterministic
  kPaced,     ///< steps follow the wall clock; nobody is waited for
};

/// Wall-clock period of the RUNNING health heartbeat.
inline constexpr auto kHealthPeriod = std::chrono::seconds(1);
/// Lockstep: a step that has not completed after this long is granted again
/// and its samples written again. A reader that matched its writer only after
/// the write can miss a transient-local sample (Fast DDS issue #3822), which
/// would otherwise stall the rig; every reader drops the copies it holds.
inline constexpr auto kResendAfter = std::chrono::seconds(2);

/// What every node needs to know about its place in the rig.
struct NodeOptions {
  std::string name;                 ///< component name, unique in the rig
  Schedule schedule;                ///< every scheduled component's divider
  Pacing pacing = Pacing::kLockstep;
  std::chrono::nanoseconds period{100'000'000};   ///< [ns] base step period (paced waits)
  std::chrono::milliseconds peer_timeout{60000};  ///< [ms] for discovery
  std::chrono::milliseconds step_timeout{60000};  ///< [ms] for one step's data
  std::uint64_t seed = 1;                         ///< [-] the scenario's: picks the samples bus faults hit
  std::vector<BusFault> bus_faults;               ///< from the scenario; more arrive as FaultCmd
  /// Paced multi-process runs: where a component keeps its state after each step and
  /// the step it is about to publish (bus/Checkpoint.hpp); empty: nowhere.
  std::string checkpoint_file;
  /// Components the scenario declares as hardware bridges (role: bridge): each
  /// may publish the topics of the emulator it stands in for (Topics.hpp, producersOf).
  std::vector<std::string> bridges;
  /// Components that run elsewhere (role: external): no launcher watches their processes.
  std::vector<std::string> externals;
  /// Participants taken as the producer of every topic besides the rig's own
  /// (FLATSAT_TRUST=flatsat-replay: a component fed by `flatsat replay`).
  std::vector<std::string> trusted;
  /// A process started again mid-run (`flatsat run --restart`): it takes its state back
  /// from checkpoint_file before its first step, and steps no grant its previous
  /// process claimed.
  bool restarted = false;
  /// Lockstep over DDS with every process the launcher's (NodeArgs::shared_memory_rig):
  /// a component grants itself step k + 1 once it is through k, as its inputs
  /// stamped k + 1 are the permission (they come after the time master closed
  /// k); the time master writes a grant at step 0, on a resend and at the stop
  /// only (architecture, "Time and the step protocol").
  bool implied_grants = false;
};

/// A FaultCmd addressed to the bus as a fault; every problem (empty: valid).
std::vector<std::string> busFaultFromCommand(const msg::FaultCmd& command, BusFault& fault);

/// Raised when a node gives up: the message names the topic and step.
struct NodeFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Node;

/// A stepped input: samples kept by step until the consumer has moved past.
/// Each input guards its samples with its own lock, so a node never holds
/// its lock while it computes or publishes: a write that Fast DDS delivers
/// synchronously to a reader of the same process cannot deadlock.
class InputBase {
 public:
  virtual ~InputBase() = default;
  /// Holds the sample due at step k (stamped k - k mod producer divider).
  virtual bool has(std::uint64_t k) const = 0;
  /// Holds some sample stamped at or before step k.
  virtual bool hasAny(std::uint64_t k) const = 0;
  virtual void dropBefore(std::uint64_t k) = 0;
  /// Whether the writer the rig starts for this topic is matched (Node::waitForProducers).
  virtual bool producerMatched() const = 0;
  virtual const std::string& topicName() const = 0;
  /// Samples received again and passed on once (Health.copies_dropped).
  virtual std::uint64_t copiesDropped() const = 0;
};

/// A mutex taken only where samples arrive on other threads than the step's
/// (a DDS bus). A composed rig delivers and steps on one thread, where the
/// inputs' uncontended lock pairs, a hundred a step, were still two atomic
/// operations each.
class MutexIfThreaded {
 public:
  explicit MutexIfThreaded(bool threaded) : threaded_(threaded) {}
  void lock() {
    if (threaded_) mutex_.lock();
  }
  void unlock() {
    if (threaded_) mutex_.unlock();
  }

 private:
  std::mutex mutex_;
  const bool threaded_;
};

template <class Def>
class Input final : public InputBase {
 public:
  using Sample = typename Def::Type;

  /// Observes every sample as it arrives (on a Fast DDS thread).
  using Observer = std::function<void(const Sample&)>;

  /// lag_steps 1: the sample due at step k is the producer's of step k − 1 (a feedback
  /// path: the producer consumes this node's output of the same step); nothing is due
  /// at step 0. `faults` null: a tap (the recorder), which waits for and passes on
  /// every sample written; else the topic's bus faults decide which sample it holds.
  Input(Node& node, const Def& def, std::uint32_t producer_divider, Observer observer,
        std::uint32_t lag_steps, const BusFaultPlan* faults);

  /// The producer's newest sample due at or before step k. In lockstep the
  /// node waited for the one stamped k - k mod (producer divider); paced, it
  /// may be older (stale). Throws NodeFailure when there is none.
  Sample at(std::uint64_t k) const {
    return with(k, [](const Sample& sample) { return sample; });
  }
  /// f(at(k)) without copying the sample out (a truth state is a kilobyte,
  /// read by every emulator every step). f runs under the input's lock: it
  /// must neither block nor publish.
  template <class F>
  auto with(std::uint64_t k, F&& f) const;
  /// As at(k), but nothing (instead of a throw) when no sample is due yet.
  std::optional<Sample> atIfAny(std::uint64_t k) const;
  /// As atIfAny(k), but only the sample due at step k: nothing when the input
  /// holds an older one (paced and late, or a bus fault dropped or delayed
  /// the due one). For a measurement that must not be used twice.
  std::optional<Sample> dueAt(std::uint64_t k) const {
    auto sample = atIfAny(k);
    const std::uint64_t j = k - lag_;
    if (sample && sample->header().step() != j - j % divider_) return std::nullopt;
    return sample;
  }
  bool has(std::uint64_t k) const override;
  bool hasAny(std::uint64_t k) const override;
  void dropBefore(std::uint64_t k) override;
  bool producerMatched() const override { return reader_.matchedFrom(awaited_); }
  const std::string& topicName() const override { return reader_.topicName(); }
  std::uint64_t copiesDropped() const override {
    std::lock_guard lock(mutex_);
    return copies_dropped_;
  }

 private:
  /// Whether anything is due at step k (a lagged input has nothing at step 0).
  bool due(std::uint64_t k) const { return k >= lag_; }
  /// The newest sample due at or before step k; null when none is. Under mutex_.
  const Sample* heldAt(std::uint64_t k) const;
  /// The stamp of the sample held at step k: the producer's due one, or under a
  /// bus fault an older one (none: every sample so far dropped or late).
  std::optional<std::uint64_t> stampFor(std::uint64_t k) const {
    const std::uint64_t j = k - lag_;
    if (faults_ == nullptr) return j - j % divider_;
    return faults_->visibleStamp(j, divider_);
  }
  Node& node_;
  std::uint32_t divider_;
  std::uint32_t lag_;
  Observer observer_;
  const BusFaultPlan* faults_;
  mutable std::uint64_t copies_dropped_ = 0;  // guarded by mutex_; counted by resent()
  /// A sample the producer wrote again (TimeMaster's resend after a stall)
  /// that this input holds already or has consumed: dropped, so observers
  /// (the recorder) see each sample once.
  bool resent(const Sample& sample) const;
  /// Over DDS, what arrives is checked first (architecture, "Trust on the
  /// bus"): stamped far past the newest grant, it is dropped; breaking its
  /// topic's contract, it is taken in its missing form (bus/SampleChecks.hpp).
  /// Either is counted (Node::refuseSample). In process every writer is the
  /// rig's own code, and a composed step stays as cheap as it was.
  void take(const Sample& sample);
  /// Holds (or passes on) a sample that was taken.
  void accept(const Sample& sample);
  mutable MutexIfThreaded mutex_;
  StepSamples<Sample> samples_;
  std::uint64_t consumed_before_ = 0;  ///< steps below this were dropped (dropBefore) or passed on
  /// A tap in a composed rig holds no sample: every write reaches it inside
  /// the write, so there is nothing to wait for, and holding a copy of every
  /// sample for a wait that never comes cost 1.5k instructions of a 47k
  /// composed step (callgrind). It still drops a copy (a bus
  /// duplicate fault): what it passed on counts as consumed.
  const bool passes_through_;
  std::uint64_t hold_steps_ = 1;       ///< paced: steps a last sample is held for (the lease)
  /// The participants one of which must be matched before the first step: the
  /// topic's producer (or a trusted stand-in, a replay). Not a bridge alone:
  /// readers would take its first sample as the owner's and drop the
  /// producer's steps before it when the producer matched late (exclusive
  /// ownership).
  std::vector<std::string> awaited_;
  Reader<Def> reader_;
};

/// Base of every bus node: owns the inputs and outputs, the lock they share,
/// and the health topic.
class Node {
 public:
  Node(Bus& bus, NodeOptions options);
  virtual ~Node();

  const std::string& name() const { return options_.name; }
  /// Names of the topics this node subscribes to as stepped inputs, in order of addInput().
  std::vector<std::string> inputTopics() const {
    std::vector<std::string> names;
    for (const auto& input : inputs_) names.push_back(input->topicName());
    return names;
  }
  std::uint32_t dividerOf(const std::string& component) const;

  /// [steps] How far past the newest grant this node has seen a sample may be
  /// stamped. A lockstep producer is at most a step ahead of the grants a
  /// consumer has seen (its grant can come first; components otherwise
  /// trail the master, bus/StepReports.hpp); farther is a
  /// clock gone wrong or a flood, which would otherwise be held for ever.
  static constexpr std::uint64_t kStampWindowSteps = 64;
  /// Whether a sample stamped `step` is near enough the newest grant to be taken.
  bool stampedNearNow(std::uint64_t step) const {
    return step <= newest_grant_.load(std::memory_order_relaxed) + kStampWindowSteps;
  }
  /// Counts (health: samples_rejected, by topic) and logs, rate-limited, a
  /// sample this node refused; on a Fast DDS thread.
  /// `as_missing`: the sample was taken in its missing form (else dropped).
  void refuseSample(const std::string& topic, const msg::SampleHeader& header, Breach why, bool as_missing);
  /// Whose samples of `def` this node takes (Reader's WriterTrust): the
  /// topic's producer and a bridge the scenario declares for it; every
  /// writer for a topic any component publishes (StepDone, health, commands).
  template <class Def>
  WriterTrust trustFor(const Def& def);
  /// For a topic every component writes (StepDone, health): samples whose
  /// header.source is their writer's own participant; others are an intruder's.
  template <class Def>
  WriterTrust trustBySource(const Def& def) {
    WriterTrust trust;
    trust.source_is_participant = true;
    trust.producers = options_.trusted;
    trust.on_foreign = [this, topic = std::string(def.name)](const std::string& guid, const std::string& participant,
                                                             bool first, bool sample) {
      foreignWriter(topic, "the component its samples name", false, guid, participant, first, sample);
    };
    return trust;
  }

 protected:
  template <class Def>
  Input<Def>& addInput(const Def& def) {
    return emplaceInput(def, {}, 0, &bus_faults_.plan(std::string(def.name)));
  }
  /// An input that waits for and passes on every sample written, whatever
  /// the bus faults (the recorder: it records what producers wrote). In a
  /// composed rig it only passes them on (see Input::passes_through_).
  template <class Def>
  Input<Def>& addTap(const Def& def, typename Input<Def>::Observer observer) {
    return emplaceInput(def, std::move(observer), 0, nullptr);
  }
  /// An input from a producer that consumes this node's output of the same step:
  /// at step k it holds the producer's sample of step k − 1.
  template <class Def>
  Input<Def>& addFeedbackInput(const Def& def) {
    return emplaceInput(def, {}, 1, &bus_faults_.plan(std::string(def.name)));
  }
  template <class Def>
  Writer<Def>& addOutput(const Def& def) {
    auto writer = std::make_unique<WriterHolder<Def>>(bus_, def);
    auto& ref = writer->writer;
    if (def.qos == QosKind::kStepped) {
      // A bus duplicate fault: the producer writes the sample twice (bus/BusFaults.hpp).
      const BusFaultPlan& plan = bus_faults_.plan(std::string(def.name));
      ref.writeAgainWhen([&plan](const typename Def::Type& sample) { return plan.duplicated(sample.header().step()); });
    }
    outputs_.push_back(std::move(writer));
    return ref;
  }

  /// Waits until every input has matched a writer; throws NodeFailure
  /// naming the unmatched topics on timeout or shutdown.
  void waitForProducers();
  /// Waits (polling, woken by any input) until `missing()` returns an empty
  /// string; on timeout or shutdown throws NodeFailure with `what` and it.
  /// `missing` runs without mutex_: it takes it itself for the node's state.
  template <class Missing>
  void waitUntilNothingMissing(Missing&& missing, const std::string& what);
  /// Whether every input holds its sample for step k (lockstep's condition), without waiting.
  /// The caller holds mutex_.
  bool inputsIn(std::uint64_t k) const;
  /// Lockstep: waits until every input holds its sample for step k.
  /// Paced: waits at most half a period, then goes on with the newest
  /// samples; returns false when an input has none at all yet.
  bool waitForInputs(std::uint64_t k);
  /// Step k is done: drops what the inputs hold that step k + 1 does not use
  /// (paced: what step k did not use; a stale sample is held from step k on).
  void dropInputsAfter(std::uint64_t k);
  /// Waits until every output's readers acknowledged all samples.
  void flushOutputs();
  /// Writes every output's last sample again (see TimeMaster::resendStep).
  void rewriteOutputs();
  /// Lockstep: called every kResendAfter while waitForInputs(k) waits.
  virtual void onStall(std::uint64_t k) {}
  /// Figures a kind of node adds to each health sample it publishes.
  virtual void addToHealth(msg::Health&) const {}
  void publishHealth(msg::ComponentState state, std::uint64_t steps_done,
                     const std::string& message);
  /// The last health before the process ends (STOPPED, FAILED): waits up to
  /// 2 s for every reader to acknowledge it, as a launcher on another host
  /// knows the component finished only from this sample.
  void publishLastHealth(msg::ComponentState state, std::uint64_t steps_done, const std::string& message);

  static bool interrupted();

  /// Wakes the node's waits: call after changing what they look at. While
  /// a lockstep wait has said what it needs (WakeWhen), only once that holds.
  void notify();
  /// For one lockstep wait, under mutex_: what must hold before waking the
  /// waiter does it any good. A wake-up per arriving sample, each finding
  /// the step still incomplete and sleeping again, made the kernel's task
  /// switches a fifth of a lockstep rig's CPU (perf). The waits
  /// still poll, so a condition that misses a case costs a poll, not a hang.
  class WakeWhen {
   public:
    /// `lock` holds mutex_ (it may be let go and taken again meanwhile).
    WakeWhen(Node& node, std::unique_lock<std::mutex>& lock, std::function<bool()> ready)
        : node_(node), lock_(lock) {
      if (!node.paced()) node_.wake_when_ = std::move(ready);
    }
    ~WakeWhen() {
      if (lock_.owns_lock()) {
        node_.wake_when_ = nullptr;
      } else {  // thrown out of a stretch without the lock
        std::lock_guard lock(node_.mutex_);
        node_.wake_when_ = nullptr;
      }
    }
    WakeWhen(const WakeWhen&) = delete;
    WakeWhen& operator=(const WakeWhen&) = delete;

   private:
    Node& node_;
    std::unique_lock<std::mutex>& lock_;
  };

  bool paced() const { return options_.pacing == Pacing::kPaced; }

  /// A grant for step k arrived: samples stamped up to k + kStampWindowSteps are taken from now on.
  void granted(std::uint64_t k) {
    std::uint64_t seen = newest_grant_.load(std::memory_order_relaxed);
    while (k > seen && !newest_grant_.compare_exchange_weak(seen, k, std::memory_order_relaxed)) {
    }
  }
  /// A writer that is not its topic's producer, as first seen: its GUID, its
  /// participant's name and the newest step granted then.
  struct Intruder {
    std::string topic, writer, participant;
    std::uint64_t step = 0;
  };
  /// The intruders seen so far, from the `from`-th on: the recorder keeps them
  /// in the recording. Data rather than a callback, as the first may come
  /// while a derived node is still being constructed.
  std::vector<Intruder> intrudersFrom(std::size_t from) const;
  /// The newest step granted that this node has seen.
  std::uint64_t newestGrant() const { return newest_grant_.load(std::memory_order_relaxed); }
  /// Throws NodeFailure when something seen on the bus ended this node's run
  /// (an intruder on a stepped topic in lockstep). The caller holds mutex_.
  void throwIfFatal() const {
    if (fatal_set_.load(std::memory_order_relaxed)) throw NodeFailure(fatal_);
  }
  /// Actuator commands held to their limits (the dynamics server: health commands_clamped).
  std::atomic<std::uint64_t> commands_clamped_{0};

  Bus& bus_;
  NodeOptions options_;
  /// Paced: steps that went on with an input not fresh (a deadline miss).
  /// The rig's step this node handled last (Health.step_reached): call as each step ends.
  void reachedStep(std::uint64_t k) { step_reached_ = k; }
  std::uint64_t step_reached_ = 0;
  std::uint64_t stale_inputs_ = 0;
  /// Paced: deadline periods an input's producer let pass without a sample.
  std::atomic<std::uint64_t> deadlines_missed_{0};
  /// An input's deadline passed (paced stepped topics' deadline QoS), on a Fast DDS thread.
  void inputLate(const std::string& topic, const std::string& producer);
  /// This node handled the run's last step: its producers publish nothing
  /// more, so a deadline that passes from now on is no one's miss.
  void lastStepReached() { last_step_reached_.store(true, std::memory_order_relaxed); }
  std::atomic<bool> last_step_reached_{false};
  /// Paced: grants skipped because the node fell behind the wall clock.
  std::uint64_t overruns_ = 0;
  /// Guards the node's own bookkeeping (grants, done sets, states) and the
  /// waits; never held while computing or publishing.
  std::mutex mutex_;
  std::condition_variable changed_;
  std::function<bool()> wake_when_;  ///< set by WakeWhen; under mutex_
  /// mutex_ for bookkeeping that samples reach on middleware threads; in
  /// process (a composed rig) they arrive on the stepping thread itself, and
  /// the lock is left untaken: a lock pair costs an atomic each way, and the
  /// grants and StepDones took a few dozen a step.
  std::unique_lock<std::mutex> lockIfThreaded() {
    return inProcess() ? std::unique_lock(mutex_, std::defer_lock) : std::unique_lock(mutex_);
  }
  /// On a composed rig's in-process bus: every sample arrives on the stepping thread.
  bool inProcess() const { return bus_.localHub() != nullptr; }

 private:
  template <class Def> friend class Input;
  struct OutputBase {
    virtual ~OutputBase() = default;
    virtual bool flush() = 0;
    virtual void rewrite() = 0;
  };
  template <class Def>
  struct WriterHolder final : OutputBase {
    WriterHolder(Bus& bus, const Def& def) : writer(bus, def) {}
    bool flush() override { return writer.waitForAcknowledgments(std::chrono::seconds(5)); }
    void rewrite() override { writer.rewriteLast(); }
    Writer<Def> writer;
  };
  template <class Def>
  Input<Def>& emplaceInput(const Def& def, typename Input<Def>::Observer observer, std::uint32_t lag,
                           const BusFaultPlan* faults) {
    auto input = std::make_unique<Input<Def>>(*this, def, dividerOf(std::string(def.producer)),
                                              std::move(observer), lag, faults);
    auto& ref = *input;
    inputs_.push_back(std::move(input));
    return ref;
  }
  /// A writer that trustFor() does not take matched (`sample` false) or wrote
  /// a sample, which was dropped; `first`: the first report of it.
  void foreignWriter(const std::string& topic, const std::string& expected, bool fatal, const std::string& guid,
                     const std::string& participant, bool first, bool sample);
  std::atomic<std::uint64_t> newest_grant_{0};
  std::string fatal_;  // guarded by mutex_; see throwIfFatal()
  std::atomic<bool> fatal_set_{false};  // fatal_ is set
  mutable std::mutex refused_mutex_;
  std::map<std::string, std::uint64_t> refused_;  // by topic, under refused_mutex_
  std::uint64_t refused_total_ = 0;               // under refused_mutex_
  std::vector<Intruder> intruders_;               // under refused_mutex_
  std::vector<std::unique_ptr<InputBase>> inputs_;
  std::vector<std::unique_ptr<OutputBase>> outputs_;
  WriterOf<topics::kHealth> health_;
  /// Asserts the health writer's liveliness every sixth of kHealthLease while the
  /// process lives, whatever its step thread does (waits, long steps); none in process.
  std::jthread liveliness_;

 protected:
  /// The bus faults this node's inputs and outputs apply: the scenario's,
  /// then each valid FaultCmd addressed to the bus.
  BusFaultTable bus_faults_;
  /// From now on each FaultCmd addressed to the bus is acknowledged through
  /// `acks` (the time master's: one answer per command in the rig).
  void acknowledgeBusFaults(CommandAcks& acks) { bus_fault_acks_.store(&acks); }

 private:
  std::atomic<CommandAcks*> bus_fault_acks_{nullptr};
  ReaderOf<topics::kFaultCmd> bus_fault_commands_;  // last: its callback uses the members above
};

template <class Def>
WriterTrust Node::trustFor(const Def& def) {
  if (def.producer.empty()) return {};
  WriterTrust trust;
  trust.producers.emplace_back(def.producer);
  trust.producers.insert(trust.producers.end(), options_.trusted.begin(), options_.trusted.end());
  const std::string bridge = std::string(def.producer) + "_bridge";
  if (std::find(options_.bridges.begin(), options_.bridges.end(), bridge) != options_.bridges.end()) {
    trust.producers.push_back(bridge);
  }
  // Lockstep cannot go on past an intruder on a stepped topic: exclusive ownership may
  // hand its samples to the readers in place of the producer's, which are then lost.
  const bool fatal = def.qos == QosKind::kStepped && !paced();
  trust.on_foreign = [this, topic = std::string(def.name), expected = std::string(def.producer), fatal](
                         const std::string& guid, const std::string& participant, bool first, bool sample) {
    foreignWriter(topic, expected, fatal, guid, participant, first, sample);
  };
  return trust;
}

/// The input type of a registry topic: InputOf<topics::kTruth>.
template <const auto& Topic>
using InputOf = Input<std::remove_cvref_t<decltype(Topic)>>;

template <class Missing>
void Node::waitUntilNothingMissing(Missing&& missing, const std::string& what) {
  const auto deadline = std::chrono::steady_clock::now() + options_.peer_timeout;
  for (;;) {
    // Asked without the node's lock: `missing` asks Fast DDS for matched
    // counts, and Fast DDS holds a reader's lock while that reader's sample
    // callback takes the node's lock (notify()), as when this node joins a
    // rig that is running already (a restart).
    const std::string left = missing();
    if (left.empty()) return;
    if (interrupted()) throw NodeFailure(options_.name + ": interrupted while " + what);
    if (std::chrono::steady_clock::now() > deadline) {
      throw NodeFailure(options_.name + ": " + what + " for " +
                        std::to_string(options_.peer_timeout.count()) + " ms; missing:" + left);
    }
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, std::chrono::milliseconds(100));
  }
}

template <class Def>
Input<Def>::Input(Node& node, const Def& def, std::uint32_t producer_divider, Observer observer,
                  std::uint32_t lag_steps, const BusFaultPlan* faults)
    : node_(node),
      divider_(producer_divider),
      lag_(lag_steps),
      observer_(std::move(observer)),
      faults_(faults),
      mutex_(!node.inProcess()),
      passes_through_(faults == nullptr && node.inProcess()),
      reader_(node.bus_, def, [this](const Sample& sample) { take(sample); },
      {},
      node.paced() ? [this](const std::string& source) { node_.inputLate(topicName(), source); }
                   : typename Reader<Def>::DeadlineCallback{},
      node.trustFor(def)) {
  // The deadline is the lease, or one and a half of the producer's own period when
  // that is longer (a 1 Hz command against a 1 s lease is not late every period).
  const auto producer_period = std::chrono::duration_cast<std::chrono::nanoseconds>(
      1.5 * producer_divider * node.options_.period);
  if (node.paced() && producer_period > node.bus_.tuning().lease) reader_.requestDeadline(producer_period);
  const auto lease_steps = static_cast<std::uint64_t>(node.bus_.tuning().lease / node.options_.period);
  hold_steps_ = std::max<std::uint64_t>(producer_divider, lease_steps);
  awaited_.emplace_back(def.producer);
  awaited_.insert(awaited_.end(), node.options_.trusted.begin(), node.options_.trusted.end());
}

template <class Def>
void Input<Def>::take(const Sample& sample) {
  if (node_.inProcess()) {
    accept(sample);
    return;
  }
  const msg::SampleHeader& header = sample.header();
  if (!node_.stampedNearNow(header.step())) {
    node_.refuseSample(topicName(), header, {"header.step", "stamped too far past the rig's newest step"}, false);
    return;
  }
  if (const Breach breach = breachOf(sample)) {
    Sample missing = sample;
    const bool as_missing = takeAsMissing(missing);
    node_.refuseSample(topicName(), header, breach, as_missing);
    if (as_missing) accept(missing);
    return;
  }
  accept(sample);
}

template <class Def>
void Input<Def>::accept(const Sample& sample) {
  if (faults_ != nullptr && faults_->dropped(sample.header().step())) return;  // never reached this reader
  if (resent(sample)) return;
  if (observer_) observer_(sample);
  if (passes_through_) {  // in process a topic's one writer delivers in step order
    consumed_before_ = sample.header().step() + 1;
    return;
  }
  {
    std::lock_guard lock(mutex_);
    samples_.insert_or_assign(sample.header().step(), sample);
  }
  node_.notify();
}

template <class Def>
bool Input<Def>::resent(const Sample& sample) const {
  const std::uint64_t step = sample.header().step();
  std::lock_guard lock(mutex_);
  const auto held = samples_.find(step);
  const bool copy = (!node_.paced() && step < consumed_before_) ||
                    (held != samples_.end() && text(held->second.header().source()) == text(sample.header().source()));
  if (copy) ++copies_dropped_;
  return copy;
}

template <class Def>
const typename Input<Def>::Sample* Input<Def>::heldAt(std::uint64_t k) const {
  if (!due(k)) return nullptr;
  const auto stamp = stampFor(k);
  if (!stamp) return nullptr;
  const auto it = samples_.upper_bound(*stamp);
  return it == samples_.begin() ? nullptr : &std::prev(it)->second;
}

template <class Def>
template <class F>
auto Input<Def>::with(std::uint64_t k, F&& f) const {
  {
    std::lock_guard lock(mutex_);
    if (const Sample* sample = heldAt(k)) return f(*sample);
  }
  throw NodeFailure("no sample on " + topicName() + " at or before step " + std::to_string(k) +
                    (faults_ != nullptr && !faults_->empty() ? " (a bus fault dropped or delayed every one so far)" : ""));
}

template <class Def>
std::optional<typename Input<Def>::Sample> Input<Def>::atIfAny(std::uint64_t k) const {
  std::lock_guard lock(mutex_);
  if (const Sample* sample = heldAt(k)) return *sample;
  return std::nullopt;
}

template <class Def>
bool Input<Def>::has(std::uint64_t k) const {
  if (!due(k) || passes_through_) return true;
  const auto stamp = stampFor(k);
  if (!stamp) return true;  // every sample so far dropped or late: nothing to wait for
  std::lock_guard lock(mutex_);
  return samples_.count(*stamp) != 0;
}

template <class Def>
bool Input<Def>::hasAny(std::uint64_t k) const {
  if (!due(k) || passes_through_) return true;
  const auto stamp = stampFor(k);
  std::lock_guard lock(mutex_);
  return stamp && !samples_.empty() && samples_.begin()->first <= *stamp;
}

template <class Def>
void Input<Def>::dropBefore(std::uint64_t k) {
  if (!due(k)) return;
  const auto stamp = stampFor(k);
  if (!stamp) return;
  std::lock_guard lock(mutex_);
  consumed_before_ = std::max(consumed_before_, *stamp);
  auto end = samples_.lower_bound(*stamp);
  // Paced, the newest sample stays until a newer one arrives: a late producer's
  // last value is held (stale) for the steps after, up to the lease, after which
  // its producer counts as dead (liveliness_lease_s) and its value is not held.
  if (node_.paced() && end != samples_.begin() && (end == samples_.end() || end->first != *stamp)) {
    const auto last = std::prev(end);
    if (*stamp - last->first <= hold_steps_) {
      --end;
    } else if (Sample missing = last->second; takeAsMissing(missing)) {
      // Its consumers then step on the topic's missing form (a dropout; its
      // header still names the last real sample, so dueAt() has nothing)
      // rather than stop: a producer gone silent, dead or silenced by an
      // intruder's ownership, stalls nobody else (architecture, "Trust on the bus").
      samples_.erase(samples_.begin(), end);
      samples_.insert_or_assign(*stamp, missing);
      return;
    }
  }
  samples_.erase(samples_.begin(), end);
}

}  // namespace flatsat::bus
