// SPDX-License-Identifier: Apache-2.0
#include "components/thruster_sequencer/ThrusterSequencerNode.hpp"

#include "bus/Convert.hpp"
#include "components/Processes.hpp"
#include "components/common/StateJson.hpp"
#include "components/station_keeping/FiringTable.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::thruster_sequencer {

namespace {

msg::ThrusterCmd toMessage(const AngleOnlySequencerOutput& out, double pulse_delta_rate_rad_s, bool angle_valid) {
  msg::ThrusterCmd m;
  bus::put(m.on_time_s(), out.on_time_s);
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

msg::ThrusterCmd toMessage(const ThrusterMomentumDumpingOutput& out) {
  msg::ThrusterCmd m;
  bus::put(m.on_time_s(), out.on_time_s);
  m.dumping(out.active);
  bus::put(m.h_wheels_body_Nms(), out.h_B_Nms);
  return m;
}

/// The plan's firings on the plant's thrusters, the seed's six in numbering
/// order: thruster 20 + 2 i is index i.
std::vector<ScheduledFiring> scheduled(const msg::StationKeepingPlan& plan) {
  std::vector<ScheduledFiring> out;
  const std::size_t n = std::min<std::size_t>(plan.firing_count(), plan.thruster().size());
  for (std::size_t k = 0; k < n; ++k) {
    const bool dumps = station_keeping::dumpsMomentum(static_cast<station_keeping::Job>(plan.job()[k]));
    out.push_back({(plan.thruster()[k] - 20) / 2, plan.ra_rad()[k], plan.duration_s()[k], dumps});
  }
  return out;
}

void readAngleOnly(bus::ParamReader& r, AngleOnlySequencerParams& p) {
  r.read("axis_body", p.axis_B, "-");
  r.read("target_rad", p.cycle.target_rad, "rad");
  r.read("lower_limit_rad", p.cycle.lower_limit_rad, "rad");
  r.read("upper_limit_rad", p.cycle.upper_limit_rad, "rad");
  r.read("correction_interval_s", p.cycle.correction_interval_s, "s");
  r.read("braking_interval_s", p.cycle.braking_interval_s, "s");
  r.read("pulse_on_time_s", p.pulse_on_time_s, "s");
  r.read("max_duty", p.max_duty, "-");
  r.read("force_weight_m", p.force_weight_m, "m");
}

void readDumping(bus::ParamReader& r, ThrusterMomentumDumpingParams& p) {
  r.read("h_start_Nms", p.h_start_Nms, "N m s");
  r.read("h_stop_Nms", p.h_stop_Nms, "N m s");
  r.read("max_duty", p.max_duty, "-");
  r.read("force_weight_m", p.force_weight_m, "m");
}

}  // namespace

ThrusterSequencerNode::ThrusterSequencerNode(bus::Bus& bus, bus::NodeOptions options,
                                             const ThrusterSequencerParams& params)
    : Component(bus, std::move(options)) {
  if (params.mode == ThrusterSequencerParams::Mode::kAngleOnly) {
    sun_ = &addInput(bus::topics::kSunSensor);
    sequencer_.emplace(params.angle_only);
    thruster_count_ = params.angle_only.thrusters.size();
  } else if (params.mode == ThrusterSequencerParams::Mode::kMomentumDumping) {
    tach_ = &addInput(bus::topics::kWheelTach);
    dumping_.emplace(params.dumping);
    thruster_count_ = params.dumping.thrusters.size();
  } else {
    plan_ = &addInput(bus::topics::kStationKeepingPlan);
    truth_ = &addInput(bus::topics::kTruth);
    firings_.emplace(params.station_keeping);
    step_s_ = params.station_keeping.step_s;
    if (params.gimbal_dumping) {
      tach_ = &addInput(bus::topics::kWheelTach);
      gimbal_dumping_.emplace(*params.gimbal_dumping);
    }
    thruster_count_ = static_cast<std::size_t>(params.station_keeping.thruster_count);
  }
}

nlohmann::json ThrusterSequencerNode::saveState() const {
  if (firings_) return nlohmann::json::object();
  if (dumping_) {
    const auto s = dumping_->state();
    return {{"dumping", s.dumping},
            {"owed_s", state_json::matrix(s.owed_s)},
            {"last_wheel_speed_rad_s", state_json::matrix(last_speed_rad_s_)}};
  }
  const auto s = sequencer_->state();
  return {{"phase", static_cast<int>(s.cycle.phase)},
          {"side", s.cycle.side},
          {"correction_count", s.cycle.correction_count},
          {"braking_count", s.cycle.braking_count},
          {"braking_remaining", s.cycle.braking_remaining},
          {"fired", s.cycle.fired},
          {"last_pulse_ns", s.cycle.last_pulse_ns},
          {"owed_s", state_json::matrix(s.owed_s)}};
}

void ThrusterSequencerNode::restoreState(const nlohmann::json& j) {
  if (firings_) return;
  if (dumping_) {
    ThrusterMomentumDumpingState s;
    s.dumping = j.at("dumping").get<bool>();
    state_json::read(j, "owed_s", s.owed_s);
    state_json::read(j, "last_wheel_speed_rad_s", last_speed_rad_s_);
    dumping_->restore(s);
    return;
  }
  AngleOnlySequencerState s;
  const int phase = j.at("phase").get<int>();
  if (phase < 0 || phase > static_cast<int>(LimitCyclePhase::kHolding)) {
    throw std::invalid_argument("phase: " + std::to_string(phase) + " is no limit-cycle phase");
  }
  s.cycle.phase = static_cast<LimitCyclePhase>(phase);
  s.cycle.side = j.at("side").get<int>();
  s.cycle.correction_count = j.at("correction_count").get<int>();
  s.cycle.braking_count = j.at("braking_count").get<int>();
  s.cycle.braking_remaining = j.at("braking_remaining").get<int>();
  s.cycle.fired = j.at("fired").get<bool>();
  s.cycle.last_pulse_ns = j.at("last_pulse_ns").get<std::int64_t>();
  state_json::read(j, "owed_s", s.owed_s);
  sequencer_->restore(s);
}

void ThrusterSequencerNode::step(const bus::StepContext& ctx) {
  msg::ThrusterCmd message;
  if (sequencer_) {
    const auto sun = sun_->at(ctx.step);
    message = toMessage(sequencer_->step({bus::vec3(sun.sun_body_unit()), sun.valid()}, ctx.sim_time_ns),
                        sequencer_->pulseDeltaRate_rad_s(1), sun.valid());
  } else if (dumping_) {
    const auto tach = tach_->at(ctx.step);
    if (tach.valid()) last_speed_rad_s_ = bus::vec4(tach.wheel_speed_rad_s());
    message = toMessage(dumping_->step(last_speed_rad_s_, ctx.sim_time_ns));
  } else {
    if (const auto plan = plan_->at(ctx.step); plan.plan_count() > 0) firings_->plan(plan.plan_step(), scheduled(plan));
    const Eigen::Vector3d r = truth_->with(ctx.step, [](const msg::TruthState& t) { return bus::vec3(t.r_inertial_m()); });
    const StationKeepingFiringsOutput out = firings_->step(std::atan2(r.y(), r.x()));
    bus::put(message.on_time_s(), out.on_time_s);
    if (gimbal_dumping_) {
      const auto tach = tach_->at(ctx.step);
      if (tach.valid()) last_speed_rad_s_ = bus::vec4(tach.wheel_speed_rad_s());
      const sim::ThrusterGimbals gimbals =
          gimbal_dumping_->angles(out.on_time_s, out.dump_left_s, last_speed_rad_s_, step_s_);
      std::copy(gimbals.data(), gimbals.data() + gimbals.size(), message.gimbal_rad().begin());
      message.dumping(!gimbals.isZero(0.0));
    }
  }
  message.thruster_count(static_cast<std::uint32_t>(thruster_count_));
  bus::stamp(message.header(), ctx, name());
  command_.write(message);
}

ThrusterSequencerParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                   const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  const vehicle::VehicleDescription& known = vehicle.onboard;  // flight software sees only this
  const double step_s = scenario.componentStep_s(args.name);
  ThrusterSequencerParams p;
  auto r = scenario.componentParams(args.name, problems);
  std::string mode = "angle_only";
  r.read("mode", mode);
  if (mode == "momentum_dumping") {
    p.mode = ThrusterSequencerParams::Mode::kMomentumDumping;
    auto& d = p.dumping;
    d.thrusters = known.thrusters;
    d.wheels = wheelGeometryOf(known.body);
    d.step_s = step_s;
    if (!scenario.hasComponent("wheel_tach")) r.problem("mode", "momentum_dumping needs a wheel_tach in the rig");
    readDumping(r, d);
    r.problems(d.validate());
  } else if (mode == "angle_only") {
    auto& a = p.angle_only;
    a.thrusters = known.thrusters;
    a.inertia_B_kg_m2 = known.body.J_B_kg_m2;
    a.step_s = step_s;
    a.boresight_B = known.sensors.sun_sensor_boresight_B;
    if (!scenario.hasComponent("sun_sensor")) {
      r.problem("", "needs a sun_sensor in the rig (its angle is the only input)");
    }
    readAngleOnly(r, a);
    r.problems(a.validate());
  } else if (mode == "station_keeping") {
    p.mode = ThrusterSequencerParams::Mode::kStationKeeping;
    auto& k = p.station_keeping;
    k.step_s = step_s;
    k.thruster_count = static_cast<int>(known.thrusters.size());
    if (!scenario.hasComponent("station_keeping")) r.problem("mode", "station_keeping needs a station_keeping planner in the rig");
    r.problems(k.validate());
    if (known.body.wheel_count > 0 && scenario.hasComponent("wheel_tach")) {
      GimbalDumpingParams g;
      g.thrusters = known.thrusters;
      g.wheels = wheelGeometryOf(known.body);
      r.read("dump_time_s", g.dump_time_s, "s");
      r.problems(g.validate());
      p.gimbal_dumping = g;
    }
  } else {
    r.problem("mode", "'" + mode + "' is none of angle_only, momentum_dumping, station_keeping");
  }
  r.finish();
  return p;
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<ThrusterSequencerNode>(argc, argv, "thruster_sequencer", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::thruster_sequencer
