// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>

#include "bus/FaultPort.hpp"
#include "bus/TimeMaster.hpp"
#include "components/dynamics_server/DynamicsServerParams.hpp"
#include "sim/DynamicsModel.hpp"

namespace flatsat::dynamics_server {

/// The dynamics server: time master of the lockstep rig. Publishes the truth
/// at t_k, then holds the commands stamped k over [t_k, t_k+1).
class DynamicsServerNode final : public bus::TimeMaster {
 public:
  DynamicsServerNode(bus::Bus& bus, bus::NodeOptions options, const DynamicsServerParams& params);

 private:
  void publishStep(const bus::StepContext& ctx) override;
  void advance(const bus::StepContext& ctx) override;

  bus::WriterOf<bus::topics::kTruth>& truth_ = addOutput(bus::topics::kTruth);
  bus::InputOf<bus::topics::kWheelTorqueCmd>* wheel_cmd_ = nullptr;  // if a controller runs
  bus::InputOf<bus::topics::kDipoleCmd>* dipole_cmd_ = nullptr;      // if torquers are driven
  bus::InputOf<bus::topics::kFlapCmd>* flap_cmd_ = nullptr;          // if flaps are fitted and driven
  bus::InputOf<bus::topics::kThrusterCmd>* thruster_cmd_ = nullptr;  // if a thruster sequencer runs
  /// A reaction wheel unit on the bench (DynamicsServerParams::wheels_follow): its speeds.
  bus::InputOf<bus::topics::kWheelTach>* wheel_unit_ = nullptr;
  std::string wheel_unit_name_;
  sim::RigidBodyParams body_;  // the rotors' inertia and torque limits
  bool following_unit_ = false;
  /// The motor torques that bring the plant's rotors to the unit's speeds over the step,
  /// when a fresh sample of the unit is held; none: the commands drive the rotors.
  std::optional<Eigen::Vector4d> followUnit(const bus::StepContext& ctx);
  std::optional<std::uint64_t> thruster_cmd_fired_;  // step of the last command fired: each fires once
  static constexpr std::int64_t kNoCommand = -1;
  std::int64_t wheel_cmd_age_steps_ = kNoCommand;   // of the command held over the last step
  std::int64_t dipole_cmd_age_steps_ = kNoCommand;
  int wheel_count_;
  sim::DynamicsModel model_;
  sim::ActuatorFaults faults_;
  bus::WriterOf<bus::topics::kFaultEvent>& fault_events_ = addOutput(bus::topics::kFaultEvent);
  bus::FaultPort<sim::ActuatorFault> fault_port_;
};

}  // namespace flatsat::dynamics_server
