// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/common/WheelGeometry.hpp"
#include "components/thruster_sequencer/PulseShaper.hpp"
#include "components/thruster_sequencer/ThrusterSelection.hpp"

namespace flatsat::thruster_sequencer {

/// When and how hard the thrusters dump the wheels' stored momentum.
struct ThrusterMomentumDumpingParams {
  WheelGeometry wheels;                         // [-] live wheels, spin axes, rotor inertias
  std::vector<sim::ThrusterParams> thrusters;   // [-] the spacecraft's table, at most kMaxThrusters
  double h_start_Nms = 1.0;   // [N m s] |H| above which dumping starts, > h_stop_Nms
  double h_stop_Nms = 0.1;    // [N m s] |H| below which it stops, > 0
  double max_duty = 0.5;      // [-] on fraction of a step of the most used thruster, (0, 1]
  double step_s = 0.1;        // [s] command period, > 0
  double force_weight_m = 1.0;  // [m] L weighing net force against torque in the selection, > 0

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct ThrusterMomentumDumpingOutput {
  sim::ThrusterVector on_time_s = sim::ThrusterVector::Zero();  // [s] this step's on-time per thruster
  Eigen::Vector3d h_B_Nms = Eigen::Vector3d::Zero();            // [N m s] stored wheel momentum it acted on
  Eigen::Vector3d torque_B_Nm = Eigen::Vector3d::Zero();        // [N m] mean thruster torque it commands
  bool active = false;                                          // dumping this step (hysteresis on)
};

/// Momentum dumping by thrusters, the alternative to magnetic unloading where the field is
/// weak (GEO; Sidi, Spacecraft Dynamics and Control, 1997, §7.5 momentum dumping; Wie, Space
/// Vehicle Dynamics and Control, ch. 7): with |H| past h_start the thrusters fire a torque
/// along −H (the selection's couples, so the orbit is not pushed) until |H| < h_stop. The
/// external torque changes the total momentum; the attitude controller, holding the body
/// still, takes the change out of the wheels. Pulses are sized by the duty and shaped by
/// the pulse shaper (minimum on-time, remainder).
/// The dumping's memory: whether a dump is under way, the on-times still owed (a checkpoint).
struct ThrusterMomentumDumpingState {
  bool dumping = false;                                      // [-] between h_start and h_stop
  sim::ThrusterVector owed_s = sim::ThrusterVector::Zero();  // [s] per thruster
};

class ThrusterMomentumDumping {
 public:
  using State = ThrusterMomentumDumpingState;
  using Params = ThrusterMomentumDumpingParams;
  using Output = ThrusterMomentumDumpingOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit ThrusterMomentumDumping(const Params& params);

  void reset();

  /// Wheel speeds [rad/s] relative to the body; t_ns [ns] is kept for the common API.
  Output step(const Eigen::Vector4d& wheel_speed_rad_s, std::int64_t t_ns);

  State state() const { return {dumping_, shaper_.owed_s()}; }
  void restore(const State& state) {
    dumping_ = state.dumping;
    shaper_.restore(state.owed_s);
  }

 private:
  Params params_;
  PulseShaper shaper_;
  bool dumping_ = false;
};

}  // namespace flatsat::thruster_sequencer
