// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryAngleOnly.hpp"

#include <algorithm>

#include "bus/Convert.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
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
  using CmdDef = std::remove_cvref_t<decltype(bus::topics::kThrusterCmd)>;
  recording.forEach(std::string(bus::topics::kThrusterCmd.name),
                    [&](std::uint64_t step, const std::string&, const std::vector<std::uint8_t>& bytes) {
                      const auto cmd = bus::deserialize<CmdDef>(bytes);
                      tally.add(decision(cmd));
                      delta_rate_rad_s = cmd.pulse_delta_rate_rad_s();
                      const auto& on = cmd.on_time_s();
                      const bool any = std::any_of(on.begin(), on.end(), [](double t) { return t > 0.0; });
                      if (any) last_pulse_end_s = static_cast<double>(step + 1) * scenario.step_s;
                    });

  double angle = 0.0, rate = 0.0, settle_s = 0.0;
  using TruthDef = std::remove_cvref_t<decltype(bus::topics::kTruth)>;
  recording.forEach(std::string(bus::topics::kTruth.name),
                    [&](std::uint64_t, const std::string&, const std::vector<std::uint8_t>& bytes) {
                      const auto truth = bus::deserialize<TruthDef>(bytes);
                      const double t = static_cast<double>(truth.header().sim_time_ns()) * 1e-9;
                      angle = thruster_sequencer::angleAboutAxis_rad(bus::vec3(truth.sun_body_unit()),
                                                                     params.boresight_B, params.axis_B);
                      rate = params.axis_B.dot(bus::vec3(truth.w_body_rad_s()));
                      if (angle > cycle.upper_limit_rad || angle < cycle.lower_limit_rad) settle_s = t + scenario.step_s;
                    });
  summary["correction_counts"] = tally.correction_counts;
  summary["braking_counts"] = tally.braking_counts;
  summary["total_pulses"] = tally.total;
  summary["pulse_delta_rate_deg_s"] = delta_rate_rad_s * kRadToDeg;
  summary["final_angle_deg"] = angle * kRadToDeg;
  summary["final_rate_deg_s"] = rate * kRadToDeg;
  summary["settle_time_s"] = std::max(settle_s, last_pulse_end_s);
}

}  // namespace flatsat::analysis
