// SPDX-License-Identifier: Apache-2.0
#include "sim/ActuatorFaults.hpp"

#include <cmath>

namespace flatsat::sim {

namespace {

constexpr std::array<std::pair<ActuatorFaultKind, const char*>, 5> kNames{{
    {ActuatorFaultKind::kWheelFailed, "wheel_failed"},
    {ActuatorFaultKind::kWheelStuck, "wheel_stuck"},
    {ActuatorFaultKind::kWheelDegraded, "wheel_degraded"},
    {ActuatorFaultKind::kCoilOpen, "coil_open"},
    {ActuatorFaultKind::kThrusterFailed, "thruster_failed"},
}};

bool onWheels(ActuatorFaultKind kind) {
  return kind == ActuatorFaultKind::kWheelFailed || kind == ActuatorFaultKind::kWheelStuck ||
         kind == ActuatorFaultKind::kWheelDegraded;
}

/// Sets the elements of v that `channel` names (-1: all) from f(element).
template <class Vector, class F>
void onChannel(Vector& v, int channel, F&& f) {
  for (int i = 0; i < v.size(); ++i) {
    if (channel < 0 || channel == i) v[i] = f(i, v[i]);
  }
}

}  // namespace

bool parseActuatorFaultKind(const std::string& text, ActuatorFaultKind& kind) {
  for (const auto& [k, name] : kNames) {
    if (text == name) {
      kind = k;
      return true;
    }
  }
  return false;
}

const char* toString(ActuatorFaultKind kind) {
  for (const auto& [k, name] : kNames) {
    if (k == kind) return name;
  }
  return "?";
}

std::vector<std::string> ActuatorFault::validate(int wheels, int thrusters) const {
  std::vector<std::string> errors;
  const int channels = onWheels(kind) ? wheels : kind == ActuatorFaultKind::kCoilOpen ? 3 : thrusters;
  if (channels == 0) {
    errors.push_back(std::string("kind: ") + toString(kind) + ": the spacecraft has no such actuator");
  }
  if (channel < -1 || channel >= channels) {
    errors.push_back("channel: must be -1 (all) or 0.." + std::to_string(channels - 1));
  }
  if (kind == ActuatorFaultKind::kWheelDegraded && !(magnitude >= 0.0 && magnitude <= 1.0)) {
    errors.push_back("magnitude: wheel_degraded takes the torque fraction left, in [0, 1]");
  } else if (!std::isfinite(magnitude)) {
    errors.push_back("magnitude: must be finite");
  }
  if (start_ns < 0) errors.push_back("start_s: must be >= 0");
  if (duration_ns < 0) errors.push_back("duration_s: must be >= 0 (0: to the end)");
  return errors;
}

bool ActuatorFaults::add(const ActuatorFault& fault) {
  if (count_ == kMaxFaults) return false;
  faults_[static_cast<std::size_t>(count_++)] = {fault, false, Eigen::Vector4d::Zero()};
  return true;
}

std::uint32_t ActuatorFaults::apply(ActuatorCommands& cmd, std::int64_t t_ns) {
  std::uint32_t active = 0;
  for (int i = 0; i < count_; ++i) {
    Entry& e = faults_[static_cast<std::size_t>(i)];
    if (!e.fault.activeAt(t_ns)) {
      e.latched = false;
      continue;
    }
    active |= 1u << i;
    const int channel = e.fault.channel;
    switch (e.fault.kind) {
      case ActuatorFaultKind::kWheelFailed:
        onChannel(cmd.wheel_torque_Nm, channel, [](int, double) { return 0.0; });
        break;
      case ActuatorFaultKind::kWheelStuck:
        if (!e.latched) {
          e.held_Nm = cmd.wheel_torque_Nm;
          e.latched = true;
        }
        onChannel(cmd.wheel_torque_Nm, channel, [&](int w, double) { return e.held_Nm[w]; });
        break;
      case ActuatorFaultKind::kWheelDegraded:
        onChannel(cmd.wheel_torque_Nm, channel, [&](int, double tau) { return e.fault.magnitude * tau; });
        break;
      case ActuatorFaultKind::kCoilOpen:
        onChannel(cmd.dipole_B_Am2, channel, [](int, double) { return 0.0; });
        break;
      case ActuatorFaultKind::kThrusterFailed:
        onChannel(cmd.thruster_on_time_s, channel, [](int, double) { return 0.0; });
        break;
    }
  }
  return active;
}

}  // namespace flatsat::sim
