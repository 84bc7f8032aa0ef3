// SPDX-License-Identifier: Apache-2.0
#pragma once
#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/thruster_sequencer/AngleOnlySequencer.hpp"

namespace flatsat::thruster_sequencer {

/// Seed S1 on the bus: the Sun sensor's reading in, thruster on-times out. It reads no
/// rate of any kind (gyro, estimate): the angle-only law needs none, and the rig proves it.
class ThrusterSequencerNode final : public bus::Component {
 public:
  ThrusterSequencerNode(bus::Bus& bus, bus::NodeOptions options, const AngleOnlySequencerParams& params);

 private:
  void step(const bus::StepContext& ctx) override;

  bus::InputOf<bus::topics::kSunSensor>& sun_ = addInput(bus::topics::kSunSensor);
  bus::WriterOf<bus::topics::kThrusterCmd>& command_ = addOutput(bus::topics::kThrusterCmd);
  AngleOnlySequencer sequencer_;
};

/// components.<name>: the limit cycle, pulse size and the controlled axis; the thruster
/// table and inertia from spacecraft, the boresight from components.sun_sensor, the step
/// from step_s and the rate divider.
AngleOnlySequencerParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                                    bus::ConfigProblems& problems);

}  // namespace flatsat::thruster_sequencer
