// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryAngleOnly.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "bus/Convert.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "components/Registry.hpp"
#include "components/thruster_sequencer/ThrusterSequencerNode.hpp"
#include "analysis/Conventions.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::analysis {

namespace {

thruster_sequencer::AngleOnlyLimitCycleOutput decision(const msg::ThrusterCmd& m) {
  thruster_sequencer::AngleOnlyLimitCycleOutput out;
  out.pulse = m.pulse();
  out.phase = static_cast<thruster_sequencer::LimitCyclePhase>(m.phase());
  out.correction_count = m.correction_count();
  out.braking_count = m.braking_count();
  out.braking_remaining = m.braking_remaining();
  out.braking = m.braking();
  return out;
}

}  // namespace

void summarizeThrusterSequencer(const bus::Scenario& scenario, const bus::Recording& recording,
                                nlohmann::ordered_json& summary) {
  if (!scenario.hasComponent("thruster_sequencer")) return;
  bus::ConfigProblems ignored;  // the scenario was checked before the run
  const vehicle::Vehicle craft = vehicle::readVehicle(scenario, ignored);
  const auto sequencer = thruster_sequencer::readParams(scenario, craft, {scenario.file, "thruster_sequencer", ""}, ignored);
  if (sequencer.mode != thruster_sequencer::ThrusterSequencerParams::Mode::kAngleOnly) return;
  const auto& params = sequencer.angle_only;
  const auto& cycle = params.cycle;

  thruster_sequencer::PulseTally tally;
  double last_pulse_end_s = 0.0;
  double delta_rate_rad_s = 0.0;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> brakings;  // [-] steps of each braking's first and last pulse
  using CmdDef = std::remove_cvref_t<decltype(bus::topics::kThrusterCmd)>;
  recording.forEach(std::string(bus::topics::kThrusterCmd.name),
                    [&](std::uint64_t step, const std::string&, const std::vector<std::uint8_t>& bytes) {
                      const auto cmd = bus::deserialize<CmdDef>(bytes);
                      tally.add(decision(cmd));
                      if (cmd.braking() && cmd.pulse() != 0) {
                        if (cmd.braking_count() - cmd.braking_remaining() == 1) brakings.emplace_back(step, step);
                        if (!brakings.empty()) brakings.back().second = step;
                      }
                      delta_rate_rad_s = cmd.pulse_delta_rate_rad_s();
                      const auto& on = cmd.on_time_s();
                      const bool any = std::any_of(on.begin(), on.end(), [](double t) { return t > 0.0; });
                      if (any) last_pulse_end_s = static_cast<double>(step + 1) * scenario.step_s;
                    });

  double angle = 0.0, rate = 0.0, settle_s = 0.0;
  std::vector<bool> left_range(brakings.size(), false);
  using TruthDef = std::remove_cvref_t<decltype(bus::topics::kTruth)>;
  recording.forEach(std::string(bus::topics::kTruth.name),
                    [&](std::uint64_t step, const std::string&, const std::vector<std::uint8_t>& bytes) {
                      const auto truth = bus::deserialize<TruthDef>(bytes);
                      const double t = static_cast<double>(truth.header().sim_time_ns()) * 1e-9;
                      angle = thruster_sequencer::angleAboutAxis_rad(bus::vec3(truth.sun_body_unit()),
                                                                     params.boresight_B, params.axis_B);
                      rate = params.axis_B.dot(bus::vec3(truth.w_body_rad_s()));
                      const bool outside = angle > cycle.upper_limit_rad || angle < cycle.lower_limit_rad;
                      if (outside) settle_s = t + scenario.step_s;
                      // A braking's last pulse acts over the step after it.
                      for (std::size_t b = 0; b < brakings.size(); ++b) {
                        if (outside && step > brakings[b].first && step <= brakings[b].second + 1) left_range[b] = true;
                      }
                    });
  summary["correction_counts"] = tally.correction_counts;
  summary["braking_counts"] = tally.braking_counts;
  summary["total_pulses"] = tally.total;
  summary["pulse_delta_rate_deg_s"] = delta_rate_rad_s * kRadToDeg;
  summary["final_angle_deg"] = angle * kRadToDeg;
  summary["final_rate_deg_s"] = rate * kRadToDeg;
  summary["settle_time_s"] = std::max(settle_s, last_pulse_end_s);
  summary["brakings_left_range"] = std::count(left_range.begin(), left_range.end(), true);
  if (const auto reach = angleOnlyBrakingReach(scenario, craft)) {
    summary["t2_condition_holds"] = reach->holds;
    summary["t2_condition"] = {{"drift_rate_deg_s", reach->drift_rate_rad_s * kRadToDeg},
                               {"braking_pulses", reach->braking_pulses},
                               {"travel_deg", reach->travel_rad * kRadToDeg},
                               {"room_deg", reach->room_rad * kRadToDeg},
                               {"longest_braking_interval_s", reach->longest_interval_s}};
  }
}

}  // namespace flatsat::analysis
