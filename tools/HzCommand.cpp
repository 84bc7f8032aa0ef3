// SPDX-License-Identifier: Apache-2.0
#include "tools/HzCommand.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <mutex>
#include <vector>

#include "bus/Stamp.hpp"
#include "tools/ToolBus.hpp"

namespace flatsat::tools {

namespace {

struct HzOptions {
  std::string topic;
  double seconds = 5.0;
  std::string source;  ///< only samples whose header.source is this; empty: all
  bool json = false;
  std::size_t window = 10000;  ///< the rolling readout's last N samples
  int domain = -1;
};

struct IntervalStats {
  std::size_t samples = 0;
  double rate_hz = 0, mean_s = 0, min_s = 0, max_s = 0, std_s = 0, span_s = 0;
};

IntervalStats statistics(const std::vector<Clock::time_point>& arrivals) {
  IntervalStats s;
  s.samples = arrivals.size();
  if (arrivals.size() < 2) return s;
  std::vector<double> intervals;
  for (std::size_t i = 1; i < arrivals.size(); ++i) {
    intervals.push_back(std::chrono::duration<double>(arrivals[i] - arrivals[i - 1]).count());
  }
  s.span_s = std::chrono::duration<double>(arrivals.back() - arrivals.front()).count();
  s.mean_s = s.span_s / static_cast<double>(intervals.size());
  s.rate_hz = s.mean_s > 0 ? 1.0 / s.mean_s : 0.0;
  s.min_s = *std::min_element(intervals.begin(), intervals.end());
  s.max_s = *std::max_element(intervals.begin(), intervals.end());
  double sum_sq = 0;
  for (double dt : intervals) sum_sq += (dt - s.mean_s) * (dt - s.mean_s);
  s.std_s = std::sqrt(sum_sq / static_cast<double>(intervals.size()));
  return s;
}

template <class Def>
int hz(const Def& def, const HzOptions& o) {
  ToolBus tool_bus("hz", o.domain);
  std::mutex mutex;
  std::vector<Clock::time_point> arrivals;
  bus::Reader<Def> reader(tool_bus.bus(), def, [&](const typename Def::Type& sample, const Arrival& a) {
    if (a.historical) return;  // written before we listened: not part of the stream
    if (!o.source.empty() && bus::text(sample.header().source()) != o.source) return;
    std::lock_guard lock(mutex);
    arrivals.push_back(a.wall);
  });
  if (!o.json) {
    std::cerr << "flatsat hz: " << def.name << " on domain " << tool_bus.domain() << " for "
              << o.seconds << " s\n";
  }
  // The window opens with the first sample, once discovery matched the
  // producer (kDiscoverySeconds), so it always spans `seconds` of stream.
  const auto start = Clock::now();
  auto next_readout = Clock::time_point::max();
  while (sleepUnlessInterrupted(0.02)) {
    std::lock_guard lock(mutex);
    const auto now = Clock::now();
    if (arrivals.empty() ? now - start > std::chrono::duration<double>(kDiscoverySeconds + o.seconds)
                         : now - arrivals.front() >= std::chrono::duration<double>(o.seconds)) {
      break;
    }
    if (o.json || arrivals.empty()) continue;
    // As `ros2 topic hz`: a readout every second over the last `window` samples.
    if (next_readout == Clock::time_point::max()) next_readout = arrivals.front() + std::chrono::seconds(1);
    if (now < next_readout) continue;
    next_readout += std::chrono::seconds(1);
    const auto from = arrivals.size() > o.window ? arrivals.end() - static_cast<std::ptrdiff_t>(o.window) : arrivals.begin();
    const auto r = statistics({from, arrivals.end()});
    if (r.samples < 2) continue;
    std::printf("%s: rate %.3f Hz  min %.6f s  max %.6f s  std %.6f s  window %zu\n", std::string(def.name).c_str(),
                r.rate_hz, r.min_s, r.max_s, r.std_s, r.samples);
    std::fflush(stdout);
  }
  IntervalStats s;
  {
    std::lock_guard lock(mutex);
    s = statistics(arrivals);
  }
  if (o.json) {
    nlohmann::ordered_json j{{"topic", def.name},
                             {"source", o.source},
                             {"seconds", o.seconds},
                             {"samples", s.samples},
                             {"rate_hz", s.rate_hz},
                             {"interval_s",
                              {{"mean", s.mean_s}, {"min", s.min_s}, {"max", s.max_s},
                               {"std", s.std_s}}}};
    std::cout << j.dump(2) << "\n";
  } else if (s.samples >= 2) {
    std::printf("%s: average rate %.3f Hz over %zu samples in %.2f s\n", std::string(def.name).c_str(),
                s.rate_hz, s.samples, s.span_s);
    std::printf("  interval [s]: mean %.6f  min %.6f  max %.6f  std %.6f\n", s.mean_s, s.min_s,
                s.max_s, s.std_s);
  }
  if (s.samples < 2) {
    std::cerr << "flatsat hz: " << s.samples << " sample(s) on " << def.name << " within "
              << kDiscoverySeconds + o.seconds << " s: no rate\n";
    return 1;
  }
  return 0;
}

}  // namespace

CLI::App* addHzCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<HzOptions>();
  auto* cmd = app.add_subcommand("hz", "measure a topic's rate in wall time");
  cmd->add_option("topic", options->topic, "topic name: flatsat/truth, or just truth")->required();
  cmd->add_option("-s,--seconds", options->seconds, "how long to measure, from the first sample [s] (default 5)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--source", options->source,
                  "count only samples whose header.source is this component");
  cmd->add_flag("--json", options->json, "print JSON, once, at the end");
  cmd->add_option("-w,--window", options->window, "the rolling readout's window: the last N samples (default 10000)")
      ->check(CLI::PositiveNumber);
  addDomainOption(*cmd, options->domain);
  cmd->footer(
      "Prints a readout every second over the last --window samples, and at the end the\n"
      "whole window's. Rate = 1 / mean interval between arrivals at this tool; min, max and\n"
      "std are of the interval. The window opens at the first sample (discovery takes up to\n"
      "4 s). A lockstep rig runs as fast as its slowest component, a paced one at the\n"
      "scenario's step rate.");
  cmd->callback([options, &exit_code] {
    exit_code = runForTopic(options->topic, [&](const auto& def) { return hz(def, *options); });
  });
  return cmd;
}

}  // namespace flatsat::tools
