// SPDX-License-Identifier: Apache-2.0
// Which StepDones a component sends and the time master waits for
// (bus/StepReports.hpp): the first and last steps in full, and no component
// ever so far behind that a sample it still needs has left its writer's
// 64-sample history (bus/Qos.cpp). No DDS.
#include <catch2/catch.hpp>

#include <cstdint>
#include <optional>

#include "bus/StepReports.hpp"

namespace {

using flatsat::bus::StepReports;

/// The newest step the master can close while the component has done every
/// due step up to `done_through` (none yet: nullopt) and is stuck on the next.
std::uint64_t closableThrough(const StepReports& reports, std::optional<std::uint64_t> done_through) {
  std::optional<std::uint64_t> newest_report;
  for (std::uint64_t s = 0; done_through && s <= *done_through; ++s) {
    if (reports.reportsAt(s)) newest_report = s;
  }
  std::uint64_t k = 0;
  for (; k <= reports.final_step; ++k) {
    const std::uint64_t needed = reports.neededToClose(k);
    if (reports.reportsAt(needed) && !(newest_report && *newest_report >= needed)) break;
  }
  return k;  // the first step it cannot close
}

}  // namespace

TEST_CASE("a component reports every eighth step or so, and never falls out of its writers' history",
          "[bus][step_reports]") {
  for (const std::uint64_t divider : {1, 2, 3, 5, 7, 8, 10, 25, 100}) {
    for (const std::uint64_t final_step : {0, 1, 9, 57, 1000, 1003}) {
      const StepReports reports{divider, final_step};
      CAPTURE(divider, final_step, reports.period());
      CHECK(reports.period() % divider == 0);
      CHECK(reports.period() >= std::min<std::uint64_t>(divider, StepReports::kReportEverySteps));
      CHECK(reports.reportsAt(0));                   // the first step in full
      CHECK(reports.reportsAt(reports.lastDue()));   // the last one too
      CHECK(reports.neededToClose(final_step) == reports.lastDue());
      std::uint64_t sent = 0;
      for (std::uint64_t s = 0; s <= final_step; ++s) {
        if (reports.reportsAt(s)) {
          CHECK(s % divider == 0);  // only steps it is due at
          ++sent;
        }
      }
      CHECK(sent <= final_step / reports.period() + 2);
      // Stuck before each due step d: the master runs on at most this far past d, so the
      // samples of step d it waits for are still among its writers' newest 64.
      for (std::uint64_t d = 0; d <= final_step; d += divider) {
        const std::optional<std::uint64_t> before = d == 0 ? std::nullopt : std::optional(d - divider);
        const std::uint64_t blocked_at = closableThrough(reports, before);
        CAPTURE(d, blocked_at);
        CHECK(blocked_at <= d + StepReports::kDoneTrailSteps + StepReports::kReportEverySteps);
        CHECK(blocked_at < d + 64);
        CHECK(blocked_at <= final_step);  // the last step always waits for it
      }
    }
  }
}
