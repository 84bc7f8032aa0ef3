// SPDX-License-Identifier: Apache-2.0
#include "components/thruster_sequencer/ThrusterSequencerNode.hpp"

#include <algorithm>

#include "bus/Convert.hpp"
#include "components/sun_sensor/SunSensorNode.hpp"
#include "sim/DynamicsServerParams.hpp"

namespace flatsat::thruster_sequencer {

namespace {

msg::ThrusterCmd toMessage(const AngleOnlySequencerOutput& out, std::size_t thruster_count,
                           double pulse_delta_rate_rad_s, bool angle_valid) {
  msg::ThrusterCmd m;
  bus::put(m.on_time_s(), out.on_time_s);
  m.thruster_count(static_cast<std::uint32_t>(thruster_count));
  m.angle_rad(out.angle_rad);
  m.angle_valid(angle_valid);
  m.phase(static_cast<std::uint8_t>(out.cycle.phase));
  m.pulse(static_cast<std::int16_t>(out.cycle.pulse));
  m.braking(out.cycle.braking);
  m.correction_count(out.cycle.correction_count);
  m.braking_count(out.cycle.braking_count);
  m.braking_remaining(out.cycle.braking_remaining);
  m.pulse_delta_rate_rad_s(pulse_delta_rate_rad_s);
  return m;
}

}  // namespace

ThrusterSequencerNode::ThrusterSequencerNode(bus::Bus& bus, bus::NodeOptions options,
                                             const AngleOnlySequencerParams& params)
    : Component(bus, std::move(options)), sequencer_(params) {}

void ThrusterSequencerNode::step(const bus::StepContext& ctx) {
  const auto sun = sun_.at(ctx.step);
  const bool valid = sun.valid();
  auto message = toMessage(sequencer_.step({bus::vec3(sun.sun_body_unit()), valid}, ctx.sim_time_ns),
                           sequencer_.params().thrusters.size(), sequencer_.pulseDeltaRate_rad_s(1), valid);
  message.header(bus::makeHeader(ctx, name()));
  command_.write(message);
}

AngleOnlySequencerParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                                    bus::ConfigProblems& problems) {
  bus::ConfigProblems reported_by_their_owners;  // the dynamics server and the Sun sensor
  const auto plant = sim::readPlant(scenario, reported_by_their_owners);
  AngleOnlySequencerParams p;
  p.thrusters = plant.thrusters;
  p.inertia_B_kg_m2 = plant.body.J_B_kg_m2;
  if (scenario.hasComponent("sun_sensor")) {
    p.boresight_B = sun_sensor::readParams(scenario, {args.scenario, "sun_sensor", ""},
                                           reported_by_their_owners)
                        .model.boresight_B;
  }
  const auto schedule = scenario.schedule();
  const auto divider = schedule.count(args.name) ? schedule.at(args.name) : 1U;
  p.step_s = scenario.step_s * divider;
  auto r = scenario.componentParams(args.name, problems);
  if (!scenario.hasComponent("sun_sensor")) r.problem("", "needs a sun_sensor in the rig (its angle is the only input)");
  r.read("axis_body", p.axis_B, "-");
  r.read("target_rad", p.cycle.target_rad, "rad");
  r.read("lower_limit_rad", p.cycle.lower_limit_rad, "rad");
  r.read("upper_limit_rad", p.cycle.upper_limit_rad, "rad");
  r.read("correction_interval_s", p.cycle.correction_interval_s, "s");
  r.read("braking_interval_s", p.cycle.braking_interval_s, "s");
  r.read("pulse_on_time_s", p.pulse_on_time_s, "s");
  r.read("max_duty", p.max_duty, "-");
  r.read("force_weight_m", p.force_weight_m, "m");
  r.problems(p.validate());
  r.finish();
  return p;
}

}  // namespace flatsat::thruster_sequencer
