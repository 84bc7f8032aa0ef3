// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "bus/Component.hpp"
#include "bus/TimeMaster.hpp"

namespace flatsat::bus {

/// Runs a lockstep rig whose nodes share one in-process bus (LocalHub) on
/// the calling thread, in data-flow order like Basilisk's task scheduler:
/// at each step the time master publishes its data and the grant, every
/// component whose inputs are in takes its turn (its outputs reach the
/// readers inside its writes), then the time master applies the step. The
/// protocol and the samples are those of the multi-process rig, so the
/// recording is the same; only the hops between processes are gone.
///
/// The order is found at step 0, where every component is due: a component
/// takes its turn once its inputs are in, and the order in which they went
/// is kept for the later steps (feedback inputs lag a step, so they never
/// hold a turn back). A step at which no waiting component can go on is a
/// configuration error and throws NodeFailure naming the blocked ones.
class ComposedScheduler {
 public:
  ComposedScheduler(TimeMaster& master, std::vector<Component*> components);

  /// Start, every step, stop. `after_step(k)` runs after step k (progress).
  /// Throws NodeFailure naming the node that failed, or on SIGINT/SIGTERM.
  void run(const std::function<void(std::uint64_t)>& after_step = {});

  /// run() in parts, for several rigs stepped side by side on one thread.
  void start();
  void step(std::uint64_t k);
  void stop();
  std::uint64_t finalStep() const { return master_.finalStep(); }

 private:
  void runStep(std::uint64_t k);

  TimeMaster& master_;
  std::vector<Component*> order_;
  std::vector<Component*> went_;  // this step's turns, in the order taken
  std::vector<bool> done_;        // by index into order_: took its turn this step
};

}  // namespace flatsat::bus
