// SPDX-License-Identifier: Apache-2.0
// Actuator faults against their definitions (sim/ActuatorFaults.hpp): a failed
// wheel gives no torque, a stuck one holds the torque it had, a degraded one
// gives its fraction, an open coil no dipole, a failed thruster no on-time;
// only on their channel and only while they act.
#include <catch2/catch.hpp>

#include "sim/ActuatorFaults.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat::sim;

namespace {

ActuatorCommands commands(double scale) {
  ActuatorCommands cmd;
  cmd.wheel_torque_Nm = scale * Eigen::Vector4d(0.01, -0.02, 0.03, -0.04);
  cmd.dipole_B_Am2 = scale * Eigen::Vector3d(5.0, -6.0, 7.0);
  cmd.thruster_on_time_s.head<4>() = scale * Eigen::Vector4d(0.01, 0.02, 0.03, 0.04);
  return cmd;
}

ActuatorFault fault(ActuatorFaultKind kind, int channel, double magnitude = 0.0, std::int64_t start = 0,
                    std::int64_t duration = 0) {
  return {kind, channel, magnitude, start, duration};
}

}  // namespace

TEST_CASE("Actuator faults act on their channel as defined", "[sim][faults]") {
  const ActuatorCommands nominal = commands(1.0);
  ActuatorFaults faults;
  SECTION("wheel_failed: no motor torque on that wheel") {
    faults.add(fault(ActuatorFaultKind::kWheelFailed, 2));
    ActuatorCommands cmd = nominal;
    CHECK(faults.apply(cmd, 0) == 1u);
    CHECK(cmd.wheel_torque_Nm == Eigen::Vector4d(0.01, -0.02, 0.0, -0.04));
    CHECK(cmd.dipole_B_Am2 == nominal.dipole_B_Am2);
  }
  SECTION("wheel_degraded: the fraction of the command, on every wheel with channel -1") {
    faults.add(fault(ActuatorFaultKind::kWheelDegraded, -1, 0.25));
    ActuatorCommands cmd = nominal;
    faults.apply(cmd, 0);
    CHECK((cmd.wheel_torque_Nm - 0.25 * nominal.wheel_torque_Nm).norm() < 1e-18);
  }
  SECTION("wheel_stuck: holds the torque of its first step, then lets go") {
    faults.add(fault(ActuatorFaultKind::kWheelStuck, 1, 0.0, 2 * kSecond, 3 * kSecond));
    ActuatorCommands before = commands(1.0);
    CHECK(faults.apply(before, 1 * kSecond) == 0u);
    CHECK(before.wheel_torque_Nm == nominal.wheel_torque_Nm);
    ActuatorCommands first = commands(2.0);
    CHECK(faults.apply(first, 2 * kSecond) == 1u);
    CHECK(first.wheel_torque_Nm[1] == -0.04);  // taken from the command at the start
    ActuatorCommands later = commands(-3.0);
    faults.apply(later, 4 * kSecond);
    CHECK(later.wheel_torque_Nm[1] == -0.04);  // held whatever is commanded
    CHECK(later.wheel_torque_Nm[0] == -0.03);  // the other wheels follow their commands
    ActuatorCommands after = commands(-3.0);
    CHECK(faults.apply(after, 5 * kSecond) == 0u);  // [start, start + duration)
    CHECK(after.wheel_torque_Nm[1] == 0.06);
  }
  SECTION("coil_open: no dipole on that axis") {
    faults.add(fault(ActuatorFaultKind::kCoilOpen, 0));
    ActuatorCommands cmd = nominal;
    faults.apply(cmd, 0);
    CHECK(cmd.dipole_B_Am2 == Eigen::Vector3d(0.0, -6.0, 7.0));
    CHECK(cmd.wheel_torque_Nm == nominal.wheel_torque_Nm);
  }
  SECTION("thruster_failed: no on-time for that thruster") {
    faults.add(fault(ActuatorFaultKind::kThrusterFailed, 3));
    ActuatorCommands cmd = nominal;
    faults.apply(cmd, 0);
    CHECK(cmd.thruster_on_time_s.head<4>() == Eigen::Vector4d(0.01, 0.02, 0.03, 0.0));
  }
}

TEST_CASE("Actuator faults are timed and bounded", "[sim][faults]") {
  ActuatorFaults faults;
  faults.add(fault(ActuatorFaultKind::kCoilOpen, 1, 0.0, 10 * kSecond, 5 * kSecond));
  faults.add(fault(ActuatorFaultKind::kWheelFailed, 0, 0.0, 12 * kSecond));
  ActuatorCommands cmd = commands(1.0);
  CHECK(faults.apply(cmd, 9 * kSecond) == 0u);
  CHECK(faults.apply(cmd, 10 * kSecond) == 1u);
  CHECK(faults.apply(cmd, 13 * kSecond) == 3u);
  CHECK(faults.apply(cmd, 15 * kSecond) == 2u);  // the coil's window ended; the wheel stays failed
  CHECK(faults.apply(cmd, 1000 * kSecond) == 2u);
  for (int i = faults.count(); i < ActuatorFaults::kMaxFaults; ++i) {
    CHECK(faults.add(fault(ActuatorFaultKind::kCoilOpen, 2)));
  }
  CHECK_FALSE(faults.add(fault(ActuatorFaultKind::kCoilOpen, 2)));
}

TEST_CASE("Actuator faults are checked against the spacecraft's actuators", "[sim][faults]") {
  const auto has = [](const std::vector<std::string>& errors, const std::string& prefix) {
    for (const auto& e : errors) {
      if (e.rfind(prefix, 0) == 0) return true;
    }
    return false;
  };
  CHECK(fault(ActuatorFaultKind::kWheelFailed, 3).validate(4, 0).empty());
  CHECK(has(fault(ActuatorFaultKind::kWheelFailed, 4).validate(4, 0), "channel: "));
  CHECK(has(fault(ActuatorFaultKind::kThrusterFailed, 0).validate(4, 0), "kind: "));
  CHECK(has(fault(ActuatorFaultKind::kCoilOpen, 3).validate(4, 0), "channel: "));
  CHECK(has(fault(ActuatorFaultKind::kWheelDegraded, 0, 1.5).validate(4, 0), "magnitude: "));
  CHECK(has(fault(ActuatorFaultKind::kWheelDegraded, 0, -0.1).validate(4, 0), "magnitude: "));
  CHECK(has(fault(ActuatorFaultKind::kCoilOpen, 0, 0.0, -1).validate(4, 0), "start_s: "));
  ActuatorFaultKind kind;
  CHECK(parseActuatorFaultKind("thruster_failed", kind));
  CHECK(kind == ActuatorFaultKind::kThrusterFailed);
  CHECK(std::string(toString(kind)) == "thruster_failed");
  CHECK_FALSE(parseActuatorFaultKind("stuck", kind));
}
