// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <deque>
#include <optional>

#include <nlohmann/json.hpp>

#include "bus/Checkpoint.hpp"
#include "bus/Node.hpp"
#include "bus/StepReports.hpp"

namespace flatsat::bus {

/// A scheduled component: the client side of the lockstep protocol
/// (architecture, "Time and the step protocol"). At each grant k for which
/// it is due, it waits for its inputs stamped k, computes, publishes its
/// outputs stamped k and then, at the steps StepReports names, StepDone(k).
class Component : public Node {
 public:
  Component(Bus& bus, NodeOptions options);

  /// Discovery -> READY -> steps until the stop grant -> STOPPED. Throws
  /// NodeFailure (after publishing FAILED health) when it gives up.
  void run();

  // The same protocol driven by a composed rig's scheduler on one thread
  // (bus/Composed.hpp), lockstep only: start(), then turn() whenever a
  // grant may be pending, finish() after the stop grant. None of them
  // blocks on an in-process bus whose waits have zero timeouts.

  /// Producers and time master matched -> READY.
  void start();
  enum class Turn {
    kIdle,     ///< no grant pending
    kBlocked,  ///< the oldest pending grant's inputs are not all in yet
    kStepped,  ///< handled one grant (stepped when due)
    kStopped,  ///< took the stop grant
  };
  /// Handles the oldest pending grant when its inputs are in.
  Turn turn();
  /// Outputs flushed -> STOPPED.
  void finish();

 protected:
  /// One step; called with every input ready for ctx.step.
  virtual void step(const StepContext& ctx) = 0;
  /// After the last step, before the STOPPED health: whatever a peer may read
  /// once this component says it stopped (a file on a shared volume) is final here.
  virtual void beforeStopped() {}

  /// State that must survive a restart (paced `--restart`), as JSON; null:
  /// none. Kept in NodeOptions::checkpoint_file after every step it was due.
  virtual nlohmann::json saveState() const { return nullptr; }
  /// Takes back what saveState() returned, before the first step of a
  /// restarted process. Throws (nlohmann::json::exception, std::exception)
  /// on a state it cannot use; the component then starts afresh.
  virtual void restoreState(const nlohmann::json& /*state*/) {}

  /// Sees every grant as it arrives, on a middleware thread under the node's
  /// lock (it must not publish, nor wait on anything but a short lock of its
  /// own); set it before the component starts. The recorder stores them
  /// from the grants this component steps by, without a second reader (a
  /// delivery and an acknowledgement a step).
  void observeGrants(std::function<void(const msg::StepGrant&)> observer);

  /// What the RUNNING health says from now on ("stepping" until set): a
  /// change is published at once, then repeated by the heartbeat.
  void setStatus(const std::string& status);

 private:
  /// What a pending grant says. A plain struct: queuing and taking the
  /// generated message cost a default construction, a copy and an assignment,
  /// all out of line, per component and step (2 % of a composed step).
  struct Grant {
    std::uint64_t step = 0;
    std::int64_t sim_time_ns = 0;  ///< [ns]
    std::int64_t period_ns = 0;    ///< [ns]
    std::uint64_t final_step = 0;  ///< [-]
    bool stop = false;
  };
  void loop();
  /// One grant: steps when due; false for the stop grant. inputs_in: the
  /// caller found every input of the grant's step in already (turn()).
  bool handle(const Grant& grant, bool inputs_in = false);
  Grant nextGrant();
  /// NodeOptions::implied_grants: queues the grant of the step after `after`.
  void grantItself(const Grant& after);
  /// Implied grants: a step it granted itself waited bus::kResendAfter for
  /// its inputs. The rig stalls on a sample lost to a late match (Fast DDS
  /// #3822) somewhere, maybe one this component wrote last; it writes them
  /// again, as a grant sent again would have it (handle()): the time master's
  /// resend of an earlier step waits in the queue behind this step.
  void onStall(std::uint64_t k) override;
  /// --restarted: the state of the checkpoint, if there is a usable one.
  void restoreCheckpoint();
  /// --restarted: drops the grants up to `claimed`. The process it replaces may
  /// have published outputs of those, which are on the bus and in the recording
  /// already: stepping one again would publish a second sample of the same step.
  void skipGrantsThrough(std::uint64_t claimed);
  /// Writes checkpoint_ to NodeOptions::checkpoint_file; on failure logs and stops keeping it.
  void keepCheckpoint();
  Checkpoint checkpoint_;  // what checkpoint_file holds
  std::optional<std::uint64_t> skip_through_;  // guarded by mutex_
  std::chrono::steady_clock::time_point next_health_;
  std::uint32_t divider_ = 1;  // this component's, from the schedule at start()
  std::deque<Grant> grants_;
  std::function<void(const msg::StepGrant&)> grant_observer_;  // guarded by mutex_
  ReaderOf<topics::kStepGrant> grant_reader_;
  WriterOf<topics::kStepDone> done_;
  std::uint64_t steps_done_ = 0;
  std::uint64_t lockstep_grants_ = 0;  // handled, for the heartbeat's clock reads
  std::optional<std::uint64_t> granted_;  // the newest step granted
  // NodeOptions::implied_grants, guarded by mutex_: the newest step queued
  // (granted by the time master or by itself), and the master's grant as it
  // wrote it (its source, period, final step) for the recorder's copies.
  std::optional<std::uint64_t> granted_itself_;
  msg::StepGrant implied_;
  std::string status_ = "stepping";
};

}  // namespace flatsat::bus
