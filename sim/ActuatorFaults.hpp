// SPDX-License-Identifier: Apache-2.0
#pragma once
// Actuator faults (architecture, "Faults"): what the plant does with
// a command when an actuator misbehaves, timed in simulated time. The kinds
// are the actuator failure modes of FDIR practice: loss of a unit, a frozen
// output, loss of effectiveness (Zhang & Jiang, "Bibliographical review on
// reconfigurable fault-tolerant control systems", Annu. Rev. Control 32, 2008,
// §2). Pure: Eigen + std.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/Truth.hpp"

namespace flatsat::sim {

enum class ActuatorFaultKind {
  kWheelFailed,     ///< the wheel's motor gives no torque (it spins down by friction)
  kWheelStuck,      ///< the motor torque stays at its value when the fault began
  kWheelDegraded,   ///< the motor torque is magnitude × the command, 0 <= magnitude <= 1
  kCoilOpen,        ///< the torquer's coil is open: no dipole on its axis
  kThrusterFailed,  ///< the thruster delivers nothing whatever its on-time
};

/// Parses "wheel_failed", "wheel_stuck", "wheel_degraded", "coil_open", "thruster_failed".
bool parseActuatorFaultKind(const std::string& text, ActuatorFaultKind& kind);
const char* toString(ActuatorFaultKind kind);

struct ActuatorFault {
  ActuatorFaultKind kind = ActuatorFaultKind::kWheelFailed;
  int channel = -1;              // [-] wheel, coil axis or thruster index; -1 = all of that kind
  double magnitude = 0.0;        // [-] wheel_degraded: the torque fraction left, in [0, 1]
  std::int64_t start_ns = 0;     // [ns] simulated time it begins, >= 0
  std::int64_t duration_ns = 0;  // [ns] how long it lasts; 0 = for the rest of the run

  bool activeAt(std::int64_t t_ns) const {
    return t_ns >= start_ns && (duration_ns == 0 || t_ns < start_ns + duration_ns);
  }
  /// Every violation as "field: reason" for a plant with these actuators.
  std::vector<std::string> validate(int wheels, int thrusters) const;
};

/// The plant's actuator faults; apply() runs them over each step's commands.
class ActuatorFaults {
 public:
  static constexpr int kMaxFaults = 16;

  /// False (and nothing changes) when kMaxFaults are already held.
  bool add(const ActuatorFault& fault);
  int count() const { return count_; }
  const ActuatorFault& fault(int i) const { return faults_[static_cast<std::size_t>(i)].fault; }

  /// Applies every fault active at t_ns (the step's start) to the commands
  /// held over the step; returns bit i set when fault i acted.
  std::uint32_t apply(ActuatorCommands& cmd, std::int64_t t_ns);

 private:
  struct Entry {
    ActuatorFault fault;
    bool latched = false;                                   // wheel_stuck: held torque taken
    Eigen::Vector4d held_Nm = Eigen::Vector4d::Zero();      // wheel_stuck: the torque it holds
  };
  std::array<Entry, kMaxFaults> faults_{};
  int count_ = 0;
};

}  // namespace flatsat::sim
