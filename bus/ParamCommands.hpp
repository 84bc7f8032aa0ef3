// SPDX-License-Identifier: Apache-2.0
#pragma once
// Parameter changes for one component (flatsat/param_cmd, `flatsat cmd param`):
// received on a Fast DDS thread, applied by the component's own thread at its
// next step, each acknowledged: accepted, or refused with its reason (and then
// counted in health by CommandAcks). The settable keys' values are announced
// on flatsat/param_state at the first step and after each accepted change
// (`flatsat param list|get`), from the step, as acknowledgements are.
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <spdlog/spdlog.h>

#include "bus/CommandAcks.hpp"
#include "bus/Convert.hpp"
#include "bus/Endpoints.hpp"
#include "bus/Inbox.hpp"
#include "bus/Stamp.hpp"

namespace flatsat::bus {

template <class Params>
class ParamCommands {
 public:
  /// A key of the component's scenario section and the number it sets.
  struct Settable {
    std::string key;
    std::function<double&(Params&)> field;
  };
  using Validate = std::function<std::vector<std::string>(const Params&)>;

  ParamCommands(Bus& bus, std::string component, std::vector<Settable> settable)
      : component_(std::move(component)),
        settable_(std::move(settable)),
        reader_(bus, topics::kParamCmd, [this](const msg::ParamCmd& c) { receive(c); }),
        state_writer_(bus, topics::kParamState) {
    if (settable_.size() > msg::ParamState().values().size()) {
      throw std::logic_error(component_ + ": more settable parameters than ParamState.values holds");
    }
  }

  /// The changes received since the last call, applied in turn to `current` and each checked
  /// with `validate` (its first problem refuses it); the new parameters when any was accepted.
  /// Called at each step the component runs; announces the values at the first and after a change.
  std::optional<Params> take(Params current, const Validate& validate, CommandAcks& acks, const StepContext& ctx) {
    bool changed = false;
    for (const auto& command : pending_.takeAll()) {
      const std::string key = text(command.key());
      const Settable* found = nullptr;
      for (const auto& s : settable_) found = s.key == key ? &s : found;
      if (found == nullptr) {
        acks.queue(command.command_id(), "param", false, key + ": not settable; " + keys() + " are");
        continue;
      }
      Params next = current;
      found->field(next) = command.value();
      if (const auto problems = validate(next); !problems.empty()) {
        acks.queue(command.command_id(), "param", false, problems.front());
        continue;
      }
      current = next;
      changed = true;
      spdlog::info("{}: {} set to {} by {}", component_, key, command.value(), text(command.header().source()));
      acks.queue(command.command_id(), "param", true, fmt::format("{} = {}", key, command.value()));
    }
    if (changed || !announced_) announce(current, ctx);
    return changed ? std::optional<Params>(current) : std::nullopt;
  }

 private:
  void announce(Params current, const StepContext& ctx) {
    msg::ParamState state;
    stamp(state.header(), ctx, component_);
    for (std::size_t i = 0; i < settable_.size(); ++i) {
      setText(state.values()[i].key(), settable_[i].key);
      state.values()[i].value(settable_[i].field(current));
    }
    state_writer_.write(state);
    announced_ = true;
  }

  void receive(const msg::ParamCmd& command) {
    if (text(command.target()) != component_) return;
    pending_.push(command);
  }
  std::string keys() const {
    std::string list;
    for (const auto& s : settable_) list += (list.empty() ? "" : ", ") + s.key;
    return list;
  }

  std::string component_;
  std::vector<Settable> settable_;
  Inbox<msg::ParamCmd> pending_;  // received, applied at the next step
  ReaderOf<topics::kParamCmd> reader_;
  WriterOf<topics::kParamState> state_writer_;
  bool announced_ = false;
};

}  // namespace flatsat::bus
