// SPDX-License-Identifier: Apache-2.0
#pragma once
// A component's side of fault injection (architecture, "Faults"): fault
// commands addressed to it, checked on arrival and taken at its next step
// with their acknowledgements, and a FaultEvent each time one of its faults
// starts or stops acting. The component's own fault table (sensor or
// actuator faults) decides what a fault does; a Fault has kind, channel and
// magnitude, and toString(kind) names the kind.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bus/CommandAcks.hpp"
#include "bus/Endpoints.hpp"
#include "bus/Inbox.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"

namespace flatsat::bus {

template <class Fault>
class FaultPort {
 public:
  /// The command as a fault; returns every problem (empty: valid).
  using Convert = std::function<std::vector<std::string>(const msg::FaultCmd&, Fault&)>;

  /// `events` is the component's own FaultEvent output (stepped with it).
  FaultPort(Bus& bus, std::string component, Convert convert, WriterOf<topics::kFaultEvent>& events)
      : component_(std::move(component)),
        convert_(std::move(convert)),
        events_(events),
        acks_(bus),
        commands_(bus, topics::kFaultCmd, [this](const msg::FaultCmd& c) { receive(c); }) {}

  /// At the start of a step: hands the faults commanded since the last step
  /// to `add` (returns false when its table is full), then publishes the
  /// acknowledgements stamped with this step.
  template <class Add>
  void take(const StepContext& ctx, Add&& add) {
    for (const auto& [fault, id] : pending_.takeAll()) {
      if (!add(fault)) {
        acks_.queue(id, "fault", false, "fault table full");
      } else {
        acks_.queue(id, "fault", true,
                    std::string(toString(fault.kind)) + " on channel " + std::to_string(fault.channel) + " added");
      }
    }
    acks_.publish(ctx, component_);
  }

  /// After applying the faults: `active` bit i says fault i (of `faultAt(i)`,
  /// i < count) acted this step; each change is published.
  template <class FaultAt>
  void publishEvents(std::uint32_t active, int count, FaultAt&& faultAt, const StepContext& ctx) {
    for (int i = 0; i < count; ++i) {
      const bool now = (active >> i) & 1u, before = (last_active_ >> i) & 1u;
      if (now == before) continue;
      const Fault& fault = faultAt(i);
      msg::FaultEvent event;
      stamp(event.header(), ctx, component_);
      setText(event.kind(), toString(fault.kind));
      event.channel(fault.channel);
      event.magnitude(fault.magnitude);
      event.active(now);
      events_.write(event);
    }
    last_active_ = active;
  }

 private:
  void receive(const msg::FaultCmd& command) {
    if (text(command.target()) != component_) return;
    Fault fault;
    const auto problems = convert_(command, fault);
    if (!problems.empty()) {
      acks_.queue(command.command_id(), "fault", false, problems.front());
      return;
    }
    pending_.push({fault, command.command_id()});
  }

  std::string component_;
  Convert convert_;
  WriterOf<topics::kFaultEvent>& events_;
  CommandAcks acks_;
  Inbox<std::pair<Fault, std::uint64_t>> pending_;  // received, applied at the next step
  std::uint32_t last_active_ = 0;
  ReaderOf<topics::kFaultCmd> commands_;  // last: it calls receive() from Fast DDS's thread
};

}  // namespace flatsat::bus
