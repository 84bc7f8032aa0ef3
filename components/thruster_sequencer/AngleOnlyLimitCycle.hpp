// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace flatsat::thruster_sequencer {

/// Limit range, pulse intervals of the angle-only correction (seed S1).
struct AngleOnlyLimitCycleParams {
  double target_rad = 0.0;                 // [rad] A1, target angle, A2 < A1 < A3
  double lower_limit_rad = -0.017453292519943295;  // [rad] A2, lower limit angle, < A1
  double upper_limit_rad = 0.017453292519943295;   // [rad] A3, upper limit angle, > A1
  double correction_interval_s = 10.0;     // [s] T1, correction pulse period, > T2
  double braking_interval_s = 1.0;         // [s] T2, braking pulse period, (0, T1)

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

enum class LimitCyclePhase : std::uint8_t {
  kAcquiring = 0,   // no correction yet: no n, no pulses, zero crosses ignored
  kCorrecting = 1,  // outside [A2, A3]: a pulse toward A1 every T1, counting n
  kCoasting = 2,    // back inside after a correction, waiting for the zero cross
  kBraking = 3,     // m = ⌊n/2⌋ pulses against the motion every T2
  kHolding = 4,     // inside, braking done (or m = 0): no pulses until the angle leaves
};

struct AngleOnlyLimitCycleInput {
  double angle_rad = 0.0;  // [rad] measured angle about the controlled axis
  bool valid = false;      // false: no measurement (no pulse, state kept)
};

struct AngleOnlyLimitCycleOutput {
  int pulse = 0;  // [-] +1 / −1: one pulse raising / lowering the rate about the axis; 0: none
  LimitCyclePhase phase = LimitCyclePhase::kAcquiring;  // after this step's decision
  int correction_count = 0;   // [-] n: pulses of the current (or last) correction
  int braking_count = 0;      // [-] m = ⌊n/2⌋ of the current (or last) braking
  int braking_remaining = 0;  // [-] braking pulses still to fire
  bool braking = false;       // [-] the pulse is a braking pulse (else a correction pulse)
};

/// Pulse counts per correction and per braking, in order, rebuilt from the decisions.
struct PulseTally {
  std::vector<int> correction_counts;  // [-] n of each correction
  std::vector<int> braking_counts;     // [-] pulses of each braking
  int total = 0;                       // [-] every pulse

  void add(const AngleOnlyLimitCycleOutput& out);
};

/// What the braking of a drift meets, for seed S1's condition on T2.
struct BrakingDrift {
  double pulse_delta_rate_rad_s = 0.0;  // [rad/s] δω, rate change of one pulse, > 0
  double drift_rate_rad_s = 0.0;        // [rad/s] the drift a correction stops and returns, any sign
  double sample_period_s = 0.1;         // [s] angle sample period: the zero cross is seen up to one late, > 0
  double pulse_on_time_s = 0.1;         // [s] a pulse's on-time, over which its δω builds up, >= 0
};

/// Seed S1's condition on T2 (JP2773738B2, description of FIG. 4: T2 "is set sufficiently
/// shorter than T1 so that the braking is completed within the limit range"), for one drift.
/// A correction stops a drift ω and brings the angle back at about ω (the seed's premise:
/// n = 2m pulses, m ≈ |ω|/δω); at the zero cross the m braking pulses, T2 apart, then take
/// the angle past A1 by
///   ω·Δt + T2·Σ_{k=1}^{m−1} (ω − kδω)⁺ + m·δω·t_on/2,
/// the first term the zero cross seen one sample late, the last the pulses' finite on-time.
/// The braking completes within the range when that is no more than the nearer limit's
/// distance from A1 (the motion may head for either).
struct BrakingReach {
  double drift_rate_rad_s = 0.0;     // [rad/s] |ω| braked, at least δω
  int braking_pulses = 0;            // [-] m
  double travel_rad = 0.0;           // [rad] angle past A1 when the braking ends
  double room_rad = 0.0;             // [rad] min(A3 − A1, A1 − A2)
  double longest_interval_s = 0.0;   // [s] the largest T2 that holds (0: none, the sampling alone is too slow)
  bool holds = false;                // travel_rad <= room_rad
};

BrakingReach brakingReach(const AngleOnlyLimitCycleParams& cycle, const BrakingDrift& drift);

/// Attitude correction from the attitude angle alone (JP2773738B2, claims 1-4; flatsat spec
/// algorithms.md S1). Outside the limit range [A2, A3] a pulse toward the target A1 fires
/// every T1 until the angle is back inside; their number n is kept (claim 4's memory). At the
/// next zero cross (the angle passes A1) m = ⌊n/2⌋ pulses fire every T2 against the motion
/// (claim 3: n/2 for even n, (n−1)/2 for odd n): a correction that stopped a drift and
/// brought the angle back used about half its pulses to reverse the rate, so half of them
/// stop it again. The direction of the motion at the zero cross is known without a rate
/// sensor: the angle comes from the side it was corrected on. The m pulses are one command
/// and run to their end even if the angle leaves the range meanwhile; correction resumes
/// after them. One instance per controlled axis.
/// The limit cycle's memory (claim 4's n and where the cycle stands): a restart's checkpoint.
struct AngleOnlyLimitCycleState {
  LimitCyclePhase phase = LimitCyclePhase::kAcquiring;  // [-]
  int side = 0;                                         // [-] +1 beyond A3, −1 beyond A2
  int correction_count = 0;                             // [-] n
  int braking_count = 0;                                // [-] m
  int braking_remaining = 0;                            // [-] braking pulses still to fire
  bool fired = false;                                   // [-] a pulse of the current phase fired
  std::int64_t last_pulse_ns = 0;                       // [ns] sample time of that pulse
};

class AngleOnlyLimitCycle {
 public:
  using State = AngleOnlyLimitCycleState;
  using Params = AngleOnlyLimitCycleParams;
  using Input = AngleOnlyLimitCycleInput;
  using Output = AngleOnlyLimitCycleOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit AngleOnlyLimitCycle(const Params& params);

  /// Back to acquisition: no n, no pending braking.
  void reset();

  /// Decides this step's pulse from the angle sampled at t_ns [ns].
  Output step(const Input& in, std::int64_t t_ns);

  const Params& params() const { return params_; }

  State state() const {
    return {phase_, side_, correction_count_, braking_count_, braking_remaining_, fired_, last_pulse_ns_};
  }
  void restore(const State& state);

 private:
  bool pulseDue(std::int64_t t_ns, std::int64_t interval_ns) const;
  Output fire(int direction, bool braking, std::int64_t t_ns);
  Output report(int pulse, bool braking = false) const;

  Params params_;
  std::int64_t correction_interval_ns_;
  std::int64_t braking_interval_ns_;
  LimitCyclePhase phase_ = LimitCyclePhase::kAcquiring;
  int side_ = 0;  // +1: corrected beyond A3, −1: beyond A2 (the side the zero cross comes from)
  int correction_count_ = 0;
  int braking_count_ = 0;
  int braking_remaining_ = 0;
  bool fired_ = false;            // a pulse of the current phase has fired
  std::int64_t last_pulse_ns_ = 0;
};

}  // namespace flatsat::thruster_sequencer
