// SPDX-License-Identifier: Apache-2.0
#pragma once
// A sensor emulator node: truth in, one reading out, the model in between.
// Each emulator supplies its model and the two mapping functions
// (IDL -> model input, model output -> IDL); nothing else differs.
#include "bus/Component.hpp"

namespace flatsat {

template <class Model, const auto& OutputTopic, auto toInput, auto toMessage>
class EmulatorNode final : public bus::Component {
 public:
  EmulatorNode(bus::Bus& bus, bus::NodeOptions options, const typename Model::Params& params)
      : Component(bus, std::move(options)), model_(params) {}

 private:
  void step(const bus::StepContext& ctx) override {
    auto message = toMessage(model_.step(toInput(truth_.at(ctx.step)), ctx.sim_time_ns));
    message.header(bus::makeHeader(ctx, name()));
    output_.write(message);
  }

  bus::InputOf<bus::topics::kTruth>& truth_ = addInput(bus::topics::kTruth);
  bus::Writer<std::remove_cvref_t<decltype(OutputTopic)>>& output_ = addOutput(OutputTopic);
  Model model_;
};

}  // namespace flatsat
