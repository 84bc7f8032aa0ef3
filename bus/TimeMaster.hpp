// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "bus/CommandAcks.hpp"
#include "bus/Node.hpp"
#include "bus/StepReports.hpp"
#include "bus/TickLateness.hpp"

namespace flatsat::bus {

/// The server side of the step protocol: owns simulated time. It starts
/// once every scheduled component reported READY; at each step k it
/// publishes the step's data and the grant; in lockstep it then waits for
/// its own inputs stamped k and the StepDones StepReports asks for (a
/// component trails by a few steps at most), paced it waits for the
/// wall-clock tick and takes the newest inputs; then it advances.
class TimeMaster : public Node {
 public:
  struct Timing {
    std::int64_t period_ns = 100'000'000;  ///< [ns] base step period, > 0
    std::uint64_t final_step = 0;          ///< [-] index of the last step
  };

  TimeMaster(Bus& bus, NodeOptions options, Timing timing);

  /// Runs every step, then the stop grant. Throws NodeFailure naming the
  /// component that failed or stalled.
  void run();

  // The same protocol driven by a composed rig's scheduler on one thread
  // (bus/Composed.hpp): start(), then for each step k beginStep(k), the
  // components' turns, endStep(k); then stop(). Lockstep only.

  /// Producers matched and every component READY -> RUNNING.
  void start();
  /// Publishes step k's data and its grant.
  void beginStep(std::uint64_t k);
  /// Waits for step k's StepDone and inputs (paced: the tick), applies them.
  void endStep(std::uint64_t k);
  /// The stop grant, flushed -> STOPPED.
  void stop();
  std::uint64_t finalStep() const { return timing_.final_step; }

 protected:
  /// Publishes what the time master produces for step k (before the grant).
  virtual void publishStep(const StepContext& ctx) = 0;
  /// Applies the inputs for step k over [t_k, t_k+1): stamped k in
  /// lockstep, the newest received when paced (check Input::hasAny).
  virtual void advance(const StepContext& ctx) = 0;

 private:
  void waitForComponents();
  /// Over DDS, after the stop: keeps this process, and with it the grants'
  /// data-sharing pool, until every component said it stopped (or failed, or
  /// its liveliness lapsed), or `timeout` passed. A best-effort grant reader
  /// (QosTuning::best_effort_readers) acknowledges nothing, so the wait for the
  /// stop grant's acknowledgements does not cover it; a reader still to take
  /// the stop from a pool that is gone never takes it.
  void waitForStoppedComponents(std::chrono::seconds timeout);
  void waitForDone(std::uint64_t k);
  /// Lockstep stall at step k: the grant and this master's samples of step k
  /// again; a component granted a step it did already writes its samples and
  /// StepDone again (Component::handle), so a sample a late-matched reader
  /// missed arrives after all (kResendAfter).
  void resendStep(std::uint64_t k, const std::string& missing);
  void onStall(std::uint64_t k) override { resendStep(k, " inputs of " + name()); }
  /// Paced: waits for the wall-clock tick, the last kTickSpin of it spinning.
  void waitForTick(std::chrono::steady_clock::time_point tick);
  static constexpr auto kTickSpin = std::chrono::microseconds(300);
  /// Paced: this thread's timer slack to 1 ns and, where permitted, SCHED_FIFO.
  void keepTime() const;
  void addToHealth(msg::Health& health) const override;
  TickLateness tick_lateness_;  ///< paced: each grant's lateness against start_ + k periods
  std::string failedComponents() const;
  /// Its last health said STOPPED or FAILED. Under mutex_.
  bool ended(const std::string& component) const;
  /// The acknowledgements of bus faults commanded since the last step, a
  /// FaultEvent for each bus fault that began or stopped acting at step k, and
  /// one (kind "lost" or "late", from the component) for each liveliness lost
  /// or regained and each component found late or on time again.
  void publishFaultEvents(const StepContext& ctx);
  /// A component's health writer lost or regained its liveliness (kHealthLease).
  /// An external component (no launcher watches its process) is lost: a
  /// lockstep run stops naming it, a paced one goes on and records it. Any
  /// other is late (its process may be starved, not dead: the launcher sees a
  /// death itself), and lockstep waits up to the step timeout.
  void livelinessChanged(const std::string& component, bool alive);
  /// Paced: marks late each running component with no health for kHealthLate.
  /// Call under mutex_.
  void findLate(std::chrono::steady_clock::time_point now);

  /// The grant of step k (at the start, every step without implied grants, and on a resend),
  /// or the stop, stamped the step after the last.
  void writeGrant(std::uint64_t k, bool stop = false);
  StepContext context(std::uint64_t k) const {
    return {k, static_cast<std::int64_t>(k) * timing_.period_ns, timing_.period_ns};
  }

  Timing timing_;
  std::chrono::steady_clock::time_point start_;        // of step 0 (paced ticks)
  std::chrono::steady_clock::time_point next_health_;  // heartbeat
  /// The step whose close a heartbeat tells (reached and granted it), due
  /// and written after the next grant rather than before it.
  std::optional<std::uint64_t> heartbeat_closed_;
  /// Each component the master waits for and the newest step it reported
  /// done. Lockstep grants k+1 only after its inputs of k and the reports
  /// StepReports asks for, and a component steps in order, so "done with
  /// step s" is "newest done >= s": a flat table scanned by name, with no
  /// allocation per StepDone (a composed rig's profile).
  struct Awaited {
    std::string component;
    StepReports reports;  ///< its divider and the run's final step
    std::optional<std::uint64_t> newest_done;
    /// Done with what closing step k needs (StepReports::neededToClose).
    bool doneWith(std::uint64_t k) const;
  };
  std::vector<Awaited> awaited_;
  std::string notDone(std::uint64_t k) const;  ///< " a b" of the components due at k and not done; under mutex_
  bool allDone(std::uint64_t k) const;         ///< notDone(k) is empty; under mutex_
  std::map<std::string, msg::ComponentState> states_;
  std::map<std::string, std::string> messages_;
  std::set<std::string> lost_;  // components whose liveliness is lost
  std::set<std::string> late_;  // paced: running components whose health is older than kHealthLate
  std::map<std::string, std::chrono::steady_clock::time_point> health_arrived_;
  struct ComponentEvent {
    std::string component;
    const char* kind;  // "lost" (liveliness) or "late" (health)
    bool active;
  };
  std::vector<ComponentEvent> component_events_;  // to publish at the next step
  ReaderOf<topics::kStepDone> done_reader_;
  ReaderOf<topics::kHealth> health_reader_;
  WriterOf<topics::kStepGrant> grant_;
  WriterOf<topics::kFaultEvent> bus_fault_events_;
  std::map<std::pair<std::string, std::size_t>, bool> bus_fault_active_;  // by topic and fault index
  CommandAcks bus_fault_acks_;
};

}  // namespace flatsat::bus
