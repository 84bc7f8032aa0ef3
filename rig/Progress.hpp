// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <mutex>
#include <vector>

#include "analysis/Quantile.hpp"
#include "analysis/RunOutcome.hpp"
#include "bus/Endpoints.hpp"
#include "bus/Topics.hpp"

namespace flatsat::rig {

using analysis::TickJitter;
using analysis::nearestRank;

/// Follows the grants to show progress and time the stepping (on the
/// launcher's DDS bus, or inside a composed rig on its in-process bus);
/// with `keep_arrivals` (paced runs) also when each grant arrived.
class Progress {
 public:
  /// What follows the steps once the first grant came.
  enum class Follow {
    kGrants,  ///< every grant (paced jitter, or in process where a grant costs nothing)
    /// The time master's health (kHealthPeriod): a lockstep rig of processes. A
    /// reader of every grant was one more delivery a step, and with it a
    /// wake-up of this process and an acknowledgement: 3 % of the rig's CPU
    /// (perf). Its last health (STOPPED, every step done) times the end.
    kMasterHealth,
  };
  Progress(bus::Bus& bus, bool show, bool keep_arrivals = false, Follow follow = Follow::kGrants)
      : show_(show), terminal_(::isatty(STDERR_FILENO) == 1), keep_arrivals_(keep_arrivals),
        grants_(std::make_unique<bus::ReaderOf<bus::topics::kStepGrant>>(
            bus, bus::topics::kStepGrant, [this](const msg::StepGrant& g) { granted(g); }, nullptr, nullptr,
            bus::WriterTrust{{std::string(bus::topics::kStepGrant.producer)}, {}})) {
    if (follow == Follow::kMasterHealth) {
      master_health_ = std::make_unique<bus::ReaderOf<bus::topics::kHealth>>(
          bus, bus::topics::kHealth, [this](const msg::Health& h) { masterReported(h); });
    }
  }

  /// Following the master's health: drops the grant reader once it saw the
  /// first grant (call from the launcher's loop, not a middleware thread).
  void poll() {
    if (master_health_ && grants_ && steps_.load() > 0) grants_.reset();
  }

  void print(bool done) {
    if (!show_) return;
    const std::uint64_t steps = steps_.load();
    if (steps == 0) {
      if (terminal_) std::fprintf(stderr, "\r  waiting for every component to be ready...");
      return;
    }
    const double wall = std::chrono::duration<double>(last_.load() - first_.load()).count();
    const double sim = static_cast<double>(steps) * static_cast<double>(period_ns_) * 1e-9;
    const double total = static_cast<double>(final_step_ + 1) * static_cast<double>(period_ns_) * 1e-9;
    const double rate = wall > 0 ? static_cast<double>(steps) / wall : 0.0;
    const double eta = rate > 0 ? static_cast<double>(final_step_ + 1 - steps) / rate : 0.0;
    // A log file gets one line per tenth of the run instead of a live line.
    const int tenth = static_cast<int>(10 * steps / (final_step_ + 1));
    if (!terminal_ && !done && tenth == last_tenth_) return;
    last_tenth_ = tenth;
    std::fprintf(stderr, "%s  sim %9.1f / %.1f s  step %llu/%llu  %7.0f steps/s  x%-7.1f eta %5.0f s%s",
                 terminal_ ? "\r" : "", sim, total, static_cast<unsigned long long>(steps),
                 static_cast<unsigned long long>(final_step_ + 1), rate,
                 wall > 0 ? sim / wall : 0.0, eta, (done || !terminal_) ? "\n" : "   ");
  }
  std::uint64_t steps() const { return steps_.load(); }
  TickJitter tickJitter() const {
    const std::lock_guard lock(arrivals_mutex_);
    TickJitter j;
    if (arrivals_.empty() || period_ns_.load() <= 0) return j;
    const auto period = std::chrono::nanoseconds(period_ns_.load());
    std::vector<double> offsets_ns;  // arrival - step * period, from an arbitrary origin
    std::uint64_t last_step = 0;
    for (const auto& [step, at] : arrivals_) {
      const auto grid = arrivals_.front().second + period * static_cast<std::int64_t>(step - arrivals_.front().first);
      offsets_ns.push_back(static_cast<double>((at - grid).count()));
      last_step = std::max(last_step, step);
    }
    const double earliest = *std::min_element(offsets_ns.begin(), offsets_ns.end());
    for (auto& o : offsets_ns) o = (o - earliest) * 1e-3;
    std::sort(offsets_ns.begin(), offsets_ns.end());
    j.p50_us = nearestRank(offsets_ns, 0.50);
    j.p99_us = nearestRank(offsets_ns, 0.99);
    j.max_us = offsets_ns.back();
    j.ticks = offsets_ns.size();
    const std::uint64_t expected = last_step + 1 - arrivals_.front().first;
    j.missed = expected > j.ticks ? expected - j.ticks : 0;
    return j;
  }
  /// [s] from `start` to the first step granted; 0 when none was.
  double startupSeconds(std::chrono::steady_clock::time_point start) const {
    return steps_.load() == 0 ? 0.0 : std::chrono::duration<double>(first_.load() - start).count();
  }
  double stepSeconds() const {
    return steps_.load() == 0 ? 0.0
                              : std::chrono::duration<double>(last_.load() - first_.load()).count();
  }

 private:
  bool show_;
  bool terminal_;
  bool keep_arrivals_;
  mutable std::mutex arrivals_mutex_;
  std::vector<std::pair<std::uint64_t, std::chrono::steady_clock::time_point>> arrivals_;
  /// Steps between clock reads when only the stepping is timed: a composed
  /// rig delivers about 170,000 grants a second, and reading the clock at
  /// each was 1.4 % of its CPU (perf). The first and the final grant are
  /// always timed, so stepSeconds() is exact; the progress line lags by at
  /// most this many steps.
  static constexpr std::uint64_t kTimedEvery = 256;

  void granted(const msg::StepGrant& g) {
    if (g.stop()) return;
    const std::uint64_t step = g.header().step();
    const bool first = steps_.load(std::memory_order_relaxed) == 0;
    if (keep_arrivals_ || first || step % kTimedEvery == 0 || step >= g.final_step()) {
      const auto now = std::chrono::steady_clock::now();
      if (keep_arrivals_) {
        const std::lock_guard lock(arrivals_mutex_);
        arrivals_.emplace_back(step, now);
      }
      if (first) first_ = now;
      last_ = now;
    }
    final_step_.store(g.final_step(), std::memory_order_relaxed);
    period_ns_.store(g.step_period_ns(), std::memory_order_relaxed);
    steps_.store(step + 1);
  }
  void masterReported(const msg::Health& h) {
    if (bus::text(h.header().source()) != bus::topics::kStepGrant.producer) return;
    if (h.state() != msg::ComponentState::RUNNING && h.state() != msg::ComponentState::STOPPED) return;
    // Before the first grant nothing is timed yet; a grant may still be newer.
    const std::uint64_t steps = steps_.load();
    if (steps == 0 || h.steps_done() < steps) return;
    last_ = std::chrono::steady_clock::now();
    steps_.store(h.steps_done());
  }

  int last_tenth_ = -1;
  std::atomic<std::uint64_t> steps_{0};
  std::atomic<std::chrono::steady_clock::time_point> first_{}, last_{};
  std::atomic<std::uint64_t> final_step_{0};
  std::atomic<std::int64_t> period_ns_{0};
  // Last: their callbacks use everything above, from middleware threads.
  std::unique_ptr<bus::ReaderOf<bus::topics::kHealth>> master_health_;
  std::unique_ptr<bus::ReaderOf<bus::topics::kStepGrant>> grants_;
};

}  // namespace flatsat::rig
