// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <algorithm>
#include <cstdint>

namespace flatsat::bus {

/// Which steps a component reports StepDone for, as both ends of the lockstep
/// protocol compute it (architecture, "Time and the step protocol"; why:
/// docs/performance.md, issue 36). The time master closes step k on its own
/// inputs stamped k: those come only once every component on their way has
/// done k, so a StepDone of those says nothing new. What the StepDones still
/// guard is how far any component (a sink, a sensor nobody on the way to the
/// master reads) may fall behind, and the first and last steps. So a component
/// reports every kReportEverySteps steps (its due ones, rounded to its divider),
/// its first step and its last due step; the master waits, closing k, for the
/// report of step k − kDoneTrailSteps when that is a reporting step. A component
/// is then at most kDoneTrailSteps + period() − 1 steps behind the master, well
/// inside the 64 samples a stepped writer keeps (bus/Qos.cpp): nothing it reads
/// has been overwritten when it gets there.
struct StepReports {
  /// [steps] Reports a component sends at most: one every this many steps.
  static constexpr std::uint64_t kReportEverySteps = 8;
  /// [steps] How far a report may trail the step the master closes. Step 0 and
  /// the last step are waited for in full: a sample a late-matched reader
  /// missed shows at step 0, where the master's resend brings it (kResendAfter).
  static constexpr std::uint64_t kDoneTrailSteps = 8;

  std::uint64_t divider = 1;     ///< [steps] the component steps when step % divider == 0, >= 1
  std::uint64_t final_step = 0;  ///< [-] the run's last step

  /// [steps] Between two reports: a multiple of the divider, at least kReportEverySteps
  /// when the divider is smaller, the divider itself when it is larger.
  std::uint64_t period() const { return divider * std::max<std::uint64_t>(1, kReportEverySteps / divider); }
  /// The last step the component is due at.
  std::uint64_t lastDue() const { return final_step - final_step % divider; }
  /// The component reports StepDone(step) after stepping it.
  bool reportsAt(std::uint64_t step) const {
    return step % divider == 0 && (step % period() == 0 || step >= lastDue());
  }
  /// The report the master needs to close step k (none: not a reporting step).
  std::uint64_t neededToClose(std::uint64_t k) const {
    if (k >= final_step) return lastDue();
    return k > kDoneTrailSteps ? k - kDoneTrailSteps : 0;
  }
};

}  // namespace flatsat::bus
