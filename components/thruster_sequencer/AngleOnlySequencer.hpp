// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/thruster_sequencer/AngleOnlyLimitCycle.hpp"
#include "components/thruster_sequencer/PulseShaper.hpp"
#include "components/thruster_sequencer/ThrusterSelection.hpp"

namespace flatsat::thruster_sequencer {

/// The S1 sequencer of one axis: limit cycle, thruster table, inertia, pulse size.
struct AngleOnlySequencerParams {
  AngleOnlyLimitCycleParams cycle;                 // [-] limit range and pulse periods (see there)
  std::vector<sim::ThrusterParams> thrusters;      // [-] the spacecraft's table, at most kMaxThrusters, one couple per sense at least
  Eigen::Matrix3d inertia_B_kg_m2 = Eigen::Matrix3d::Identity();  // [kg m²] spacecraft inertia, symmetric positive definite
  Eigen::Vector3d axis_B = Eigen::Vector3d::UnitY();       // [-] controlled axis, unit
  Eigen::Vector3d boresight_B = Eigen::Vector3d::UnitX();  // [-] angle sensor boresight, unit, ⟂ axis_B
  double pulse_on_time_s = 0.1;    // [s] on-time of the most used thruster per pulse, > 0
  double max_duty = 1.0;           // [-] largest on fraction of a step, (0, 1]
  double step_s = 0.1;             // [s] command period, > 0
  double force_weight_m = 1.0;     // [m] L weighing net force against torque in the selection, > 0

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct AngleOnlySequencerInput {
  Eigen::Vector3d sun_B_unit = Eigen::Vector3d::UnitX();  // [-] measured Sun direction, body axes
  bool valid = false;                                     // the sensor sees the Sun
};

struct AngleOnlySequencerOutput {
  sim::ThrusterVector on_time_s = sim::ThrusterVector::Zero();  // [s] this step's on-time per thruster
  AngleOnlyLimitCycleOutput cycle;  // [-] the limit cycle's decision
  double angle_rad = 0.0;           // [rad] the angle it decided on
};

/// [rad] Rotation of the body about axis_B away from the Sun as the sensor sees it: a body
/// turned by θ about a from Sun on the boresight b sees s = b cos θ + (b × a) sin θ, hence
/// θ = atan2(s·(b × a), s·b).
double angleAboutAxis_rad(const Eigen::Vector3d& sun_B, const Eigen::Vector3d& boresight_B,
                          const Eigen::Vector3d& axis_B);

/// Seed S1 on thrusters: the angle-only limit cycle (AngleOnlyLimitCycle) decides pulses,
/// the thruster selection turns a pulse's sense into on-times of couples, the pulse shaper
/// fits them into steps. The rate change of a pulse follows from the thrusters and the
/// inertia: δω = a·I⁻¹(τ t_on), τ the firing's torque.
/// The sequencer's memory: the limit cycle's and the on-times still owed (a restart's checkpoint).
struct AngleOnlySequencerState {
  AngleOnlyLimitCycleState cycle;
  sim::ThrusterVector owed_s = sim::ThrusterVector::Zero();  // [s] per thruster
};

class AngleOnlySequencer {
 public:
  using State = AngleOnlySequencerState;
  using Params = AngleOnlySequencerParams;
  using Input = AngleOnlySequencerInput;
  using Output = AngleOnlySequencerOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit AngleOnlySequencer(const Params& params);

  void reset();

  Output step(const Input& in, std::int64_t t_ns);

  /// [rad/s] rate change about the axis of one pulse of sense +1 or −1 (signed).
  double pulseDeltaRate_rad_s(int sense) const;

  const Params& params() const { return params_; }

  State state() const { return {cycle_.state(), shaper_.owed_s()}; }
  void restore(const State& state) {
    cycle_.restore(state.cycle);
    shaper_.restore(state.owed_s);
  }

 private:
  const ThrusterFiring& firing(int sense) const { return sense > 0 ? raise_ : lower_; }

  Params params_;
  ThrusterFiring raise_;  // torque along +axis
  ThrusterFiring lower_;  // torque along −axis
  AngleOnlyLimitCycle cycle_;
  PulseShaper shaper_;
};

/// Minimum on-time per thruster, I_bit / F (0 where the impulse is continuous).
sim::ThrusterVector minOnTimes_s(const std::vector<sim::ThrusterParams>& thrusters);

}  // namespace flatsat::thruster_sequencer
