// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <deque>

#include "bus/Node.hpp"

namespace flatsat::bus {

/// A scheduled component: the client side of the lockstep protocol
/// (architecture, "Time and the step protocol"). At each grant k for which
/// it is due, it waits for its inputs stamped k, computes, publishes its
/// outputs stamped k and then StepDone(k).
class Component : public Node {
 public:
  Component(Bus& bus, NodeOptions options);

  /// Discovery -> READY -> steps until the stop grant -> STOPPED. Throws
  /// NodeFailure (after publishing FAILED health) when it gives up.
  void run();

 protected:
  /// One step; called with every input ready for ctx.step.
  virtual void step(const StepContext& ctx) = 0;

  /// What the RUNNING health says from now on ("stepping" until set): a
  /// change is published at once, then repeated by the heartbeat.
  void setStatus(const std::string& status);

 private:
  void loop();
  msg::StepGrant nextGrant();
  std::deque<msg::StepGrant> grants_;
  ReaderOf<topics::kStepGrant> grant_reader_;
  WriterOf<topics::kStepDone> done_;
  std::uint64_t steps_done_ = 0;
  std::string status_ = "stepping";
};

}  // namespace flatsat::bus
