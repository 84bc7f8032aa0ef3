// SPDX-License-Identifier: Apache-2.0
#pragma once
// A sensor emulator node: truth in, one reading out, the model in between,
// then the sensor's faults (scenario `faults:` and FaultCmd topic). Each
// emulator supplies its model, the two mapping functions (IDL -> model
// input, model output -> IDL) and which output field the faults act on.
#include <mutex>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "bus/CommandAcks.hpp"
#include "bus/Component.hpp"
#include "components/common/FaultParams.hpp"

namespace flatsat {

template <class ModelParams>
struct EmulatorParams {
  ModelParams model;
  std::vector<SensorFault> faults;  // from the scenario, timed in simulated time
};

template <class Model, const auto& OutputTopic, auto toInput, auto toMessage, auto measured>
class EmulatorNode final : public bus::Component {
  using Output = typename Model::Output;
  using Vector = std::remove_cvref_t<decltype(std::declval<Output&>().*measured)>;
  static constexpr int kChannels = Vector::RowsAtCompileTime;

 public:
  using Params = EmulatorParams<typename Model::Params>;

  EmulatorNode(bus::Bus& bus, bus::NodeOptions options, const Params& params)
      : Component(bus, std::move(options)),
        commands_(bus, bus::topics::kFaultCmd,
                  [this](const msg::FaultCmd& command) { receive(command); }),
        model_(params.model),
        faults_(params.model.seed ^ 0x9e3779b97f4a7c15ULL) {
    for (const auto& fault : params.faults) faults_.add(fault);
  }

 private:
  void step(const bus::StepContext& ctx) override {
    takeCommands();
    acks_.publish(ctx, name());
    Output out = model_.step(toInput(truth_.at(ctx.step)), ctx.sim_time_ns);
    const auto result = faults_.apply(out.*measured, ctx.sim_time_ns);
    publishFaultEvents(result.active, ctx);
    auto message = toMessage(out);
    message.valid(message.valid() && result.valid);
    message.header(bus::makeHeader(ctx, name()));
    output_.write(message);
  }

  void receive(const msg::FaultCmd& command) {
    if (bus::text(command.target()) != name()) return;
    SensorFault fault;
    const auto problems = toSensorFault(command, kChannels, fault);
    if (!problems.empty()) {
      acks_.queue(command.command_id(), "fault", false, problems.front());
      return;
    }
    std::lock_guard lock(commands_mutex_);
    pending_.push_back({fault, command.command_id()});
  }

  void takeCommands() {
    std::vector<std::pair<SensorFault, std::uint64_t>> pending;
    {
      std::lock_guard lock(commands_mutex_);
      pending.swap(pending_);
    }
    for (const auto& [fault, id] : pending) {
      if (!faults_.add(fault)) {
        acks_.queue(id, "fault", false, "fault table full");
      } else {
        acks_.queue(id, "fault", true,
                    std::string(toString(fault.kind)) + " on channel " +
                        std::to_string(fault.channel) + " added");
      }
    }
  }

  void publishFaultEvents(std::uint32_t active, const bus::StepContext& ctx) {
    for (int i = 0; i < faults_.count(); ++i) {
      const bool now = (active >> i) & 1u, before = (last_active_ >> i) & 1u;
      if (now == before) continue;
      const SensorFault& fault = faults_.fault(i);
      msg::FaultEvent event;
      event.header(bus::makeHeader(ctx, name()));
      bus::setText(event.kind(), toString(fault.kind));
      event.channel(fault.channel);
      event.magnitude(fault.magnitude);
      event.active(now);
      events_.write(event);
    }
    last_active_ = active;
  }

  bus::InputOf<bus::topics::kTruth>& truth_ = addInput(bus::topics::kTruth);
  bus::WriterOf<OutputTopic>& output_ = addOutput(OutputTopic);
  bus::WriterOf<bus::topics::kFaultEvent>& events_ = addOutput(bus::topics::kFaultEvent);
  std::mutex commands_mutex_;
  // commands received (with their ids), applied at the next step
  std::vector<std::pair<SensorFault, std::uint64_t>> pending_;
  bus::CommandAcks acks_{bus_};
  bus::ReaderOf<bus::topics::kFaultCmd> commands_;
  Model model_;
  SensorFaults<kChannels> faults_;
  std::uint32_t last_active_ = 0;
};

/// components.<name>: the model's keys via `readModel(reader, params)`,
/// plus `faults:` in the measurement's unit.
template <class ModelParams, class ReadModel>
EmulatorParams<ModelParams> readEmulatorParams(const bus::Scenario& scenario,
                                               const std::string& name, int channels,
                                               std::string_view unit, bus::ConfigProblems& problems,
                                               ReadModel&& readModel) {
  EmulatorParams<ModelParams> p;
  p.model.seed = scenario.seedFor(name);
  auto r = scenario.componentParams(name, problems);
  readModel(r, p.model);
  r.read("seed", p.model.seed);
  p.faults = readSensorFaults(r, channels, unit);
  r.problems(p.model.validate());
  r.finish();
  return p;
}

}  // namespace flatsat
