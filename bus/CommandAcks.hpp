// SPDX-License-Identifier: Apache-2.0
#pragma once
// Acknowledgements of operator commands (mode, fault, param). A command is
// received on a Fast DDS thread; its acknowledgement is queued there and
// published by the component's own thread at its next step, stamped with
// the step from which the change applies. Publishing from the step keeps the
// rule "never publish from under a lock or a listener".
#include <string>
#include <vector>

#include "bus/Endpoints.hpp"
#include "bus/Inbox.hpp"
#include "bus/Stamp.hpp"
#include "bus/Topics.hpp"

namespace flatsat::bus {

class CommandAcks {
 public:
  explicit CommandAcks(Bus& bus) : bus_(bus), writer_(bus, topics::kCommandAck) {}

  /// Thread-safe; `command` is mode, fault or param. A refusal is logged and
  /// counted in the component's health.
  void queue(std::uint64_t command_id, const std::string& command, bool accepted,
             const std::string& reason) {
    if (!accepted) bus_.countRefusedCommand(command, command_id, reason);
    msg::CommandAck ack;
    ack.command_id(command_id);
    setText(ack.command(), command);
    ack.accepted(accepted);
    setText(ack.reason(), reason);
    queued_.push(ack);
  }

  /// Publishes what was queued, stamped with this step and `source`.
  void publish(const StepContext& ctx, const std::string& source) {
    for (auto& ack : queued_.takeAll()) {
      stamp(ack.header(), ctx, source);
      writer_.write(ack);
    }
  }

 private:
  Bus& bus_;
  Inbox<msg::CommandAck> queued_;
  WriterOf<topics::kCommandAck> writer_;
};

}  // namespace flatsat::bus
