// SPDX-License-Identifier: Apache-2.0
#pragma once
// A sensor emulator node: truth in, one reading out, the model in between,
// then the sensor's faults (scenario `faults:` and FaultCmd topic). Each
// emulator supplies its model, the two mapping functions (IDL -> model
// input, model output -> IDL) and which output field the faults act on.
#include <string>
#include <vector>


#include "bus/Component.hpp"
#include "bus/FaultPort.hpp"
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
        model_(params.model),
        faults_(params.model.seed ^ 0x9e3779b97f4a7c15ULL) {
    for (const auto& fault : params.faults) faults_.add(fault);
  }

 private:
  void step(const bus::StepContext& ctx) override {
    fault_port_.take(ctx, [this](const SensorFault& fault) { return faults_.add(fault); });
    Output out = model_.step(truth_.with(ctx.step, toInput), ctx.sim_time_ns);
    const auto result = faults_.apply(out.*measured, ctx.sim_time_ns);
    fault_port_.publishEvents(result.active, faults_.count(),
                              [this](int i) -> const SensorFault& { return faults_.fault(i); }, ctx);
    auto message = toMessage(out);
    message.valid(message.valid() && result.valid);
    bus::stamp(message.header(), ctx, name());
    output_.write(message);
  }

  bus::InputOf<bus::topics::kTruth>& truth_ = addInput(bus::topics::kTruth);
  bus::WriterOf<OutputTopic>& output_ = addOutput(OutputTopic);
  bus::WriterOf<bus::topics::kFaultEvent>& events_ = addOutput(bus::topics::kFaultEvent);
  Model model_;
  SensorFaults<kChannels> faults_;
  bus::FaultPort<SensorFault> fault_port_{
      bus_, name(),
      [](const msg::FaultCmd& command, SensorFault& fault) { return toSensorFault(command, kChannels, fault); },
      events_};
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
