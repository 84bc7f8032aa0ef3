// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <optional>

#include <Eigen/Core>

namespace flatsat::unloading_controller {

/// A window another component asks the coil owner for (seed S0's measurement).
struct CoilRequest {
  std::uint32_t id = 0;                               // [-] > 0; a new id asks for a new window
  Eigen::Vector3d m_B_Am2 = Eigen::Vector3d::Zero();  // [A m²] dipole for the pulse
  double quiet_s = 0.0;        // [s] coils off before the pulse, >= 0
  double pulse_s = 0.0;        // [s] dipole on, > 0
  double quiet_after_s = 0.0;  // [s] coils off after it, >= 0
  /// [A m²] > 0: hold the law's own dipole of the pulse's first step instead, when its component
  /// along m_B_Am2 is at least this and at least half its size (seed S0 reusing an unloading
  /// pulse: the unloading goes on through the window); 0: always m_B_Am2
  double law_pulse_min_Am2 = 0.0;
};

enum class CoilPhase { kIdle, kQuiet, kPulse, kQuietAfter, kDone, kRefused };

/// The window in progress or the last one finished, as applied.
struct CoilWindowReport {
  std::uint32_t request_id = 0;
  CoilPhase phase = CoilPhase::kIdle;
  std::int64_t t0_ns = 0, t1_ns = 0, pulse_end_ns = 0, t2_ns = 0;  // [ns]
  Eigen::Vector3d m_B_Am2 = Eigen::Vector3d::Zero();  // [A m²] as commanded (after the coil limits)
  bool law_pulse = false;  // m_B_Am2 is the law's, taken at t1
};

struct CoilArbiterOutput {
  Eigen::Vector3d m_B_Am2 = Eigen::Vector3d::Zero();  // [A m²] what the coils get this step
  bool window_active = false;  // a requested window holds the coils: the owner's law is off
  CoilWindowReport report;
};

/// One owner for the magnetorquers (algorithms.md): the
/// unloading law drives them unless a requested window holds them. A window runs
/// whole — quiet, pulse, quiet after — and is never interrupted or overlapped; a
/// request arriving while one runs waits until it ends. A request whose dipole a
/// coil cannot give (beyond its limit) is refused rather than silently clipped:
/// S0 divides by the dipole it asked for.
class CoilArbiter {
 public:
  /// @param max_dipole_Am2 [A m²] per-coil limit, > 0
  explicit CoilArbiter(const Eigen::Vector3d& max_dipole_Am2);

  void reset();

  /// @param law_m_B_Am2 [A m²] what the owner's own law asks for this step
  CoilArbiterOutput step(const std::optional<CoilRequest>& request,
                         const Eigen::Vector3d& law_m_B_Am2, std::int64_t t_ns);

 private:
  Eigen::Vector3d max_dipole_Am2_;
  CoilWindowReport window_;
  std::uint32_t last_served_ = 0;
  double law_pulse_min_Am2_ = 0.0;  // of the window running
  bool pulse_started_ = false;      // its dipole is fixed
};

}  // namespace flatsat::unloading_controller
