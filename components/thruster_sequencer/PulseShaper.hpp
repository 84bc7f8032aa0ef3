// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/Thrusters.hpp"

namespace flatsat::thruster_sequencer {

struct PulseShaperParams {
  double step_s = 0.1;    // [s] command period (the step the on-times fill), > 0
  double max_duty = 1.0;  // [-] largest fraction of a step one thruster may be on, (0, 1]
  sim::ThrusterVector min_on_time_s = sim::ThrusterVector::Zero();  // [s] per thruster, >= 0; 0: any on-time

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

/// Turns requested on-times into the on-times one step can carry. The minimum on-time is
/// honoured by remainder accumulation (Basilisk thrFiringRemainder; Alcorn, Allard & Schaub,
/// "Steady-state attitude and control effort sensitivity analysis of discretized thruster
/// implementations", JSR 2017, doi 10.2514/1.A33709): what a step cannot fire, because it is
/// shorter than a whole number of minimum on-times or longer than max_duty·step, is kept and
/// fired later, so the impulse asked for is delivered in full, only later. On-times are
/// whole multiples of the minimum on-time, the pulses a valve driver can resolve.
class PulseShaper {
 public:
  using Params = PulseShaperParams;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit PulseShaper(const Params& params);

  /// Forgets every owed on-time.
  void reset();

  /// Adds request_s [s] per thruster to what is owed and returns this step's on-times [s].
  sim::ThrusterVector step(const sim::ThrusterVector& request_s);

  /// [s] on-time requested but not yet commanded, per thruster.
  const sim::ThrusterVector& owed_s() const { return owed_s_; }
  /// Continues owing `owed_s` [s] (a checkpoint's).
  void restore(const sim::ThrusterVector& owed_s) { owed_s_ = owed_s; }

 private:
  Params params_;
  sim::ThrusterVector owed_s_ = sim::ThrusterVector::Zero();
};

}  // namespace flatsat::thruster_sequencer
