// SPDX-License-Identifier: Apache-2.0
#include "components/estimator/EstimatorNode.hpp"

#include <optional>

#include <algorithm>

#include "bus/Convert.hpp"
#include "sim/Frames.hpp"
#include "sim/DynamicsServerParams.hpp"

namespace flatsat::estimator {

namespace {

AttitudeEstimatorInput toInput(const msg::GyroReading& gyro, const msg::SunSensorReading& sun,
                               const std::optional<msg::MagnetometerReading>& magnetometer,
                               const ReferenceVectors& reference) {
  AttitudeEstimatorInput in;
  in.w_gyro_B_rad_s = bus::vec3(gyro.w_body_rad_s());
  in.sun_B_meas_unit = bus::vec3(sun.sun_body_unit());
  in.sun_valid = sun.valid();
  if (magnetometer) {
    in.b_B_meas_T = bus::vec3(magnetometer->b_body_T());
    in.b_valid = magnetometer->valid() && !magnetometer->saturated();
  }
  in.sun_N_ref_unit = reference.sun_N_unit;
  in.b_N_ref_T = reference.b_N_T;
  return in;
}

msg::AttitudeEstimate toMessage(const AttitudeEstimatorOutput& out) {
  msg::AttitudeEstimate m;
  bus::put(m.q_inertial_body(), out.q_NB);
  bus::put(m.w_body_rad_s(), out.w_NB_B_rad_s);
  bus::put(m.gyro_bias_body_rad_s(), out.gyro_bias_B_rad_s);
  bus::put(m.sun_body_unit(), out.sun_B_est_unit);
  m.initialized(out.initialized);
  m.sun_used(out.sun_used);
  m.field_used(out.field_used);
  return m;
}

}  // namespace

EstimatorNode::EstimatorNode(bus::Bus& bus, bus::NodeOptions options,
                             const EstimatorNodeParams& params)
    : Component(bus, std::move(options)),
      filter_(params.filter),
      reference_(params.reference),
      jd_epoch_utc_(params.jd_epoch_utc) {
  if (options_.schedule.count(std::string(bus::topics::kMagnetometer.producer))) {
    magnetometer_ = &addInput(bus::topics::kMagnetometer);
  }
  if (params.s0) {
    s0_.emplace(*params.s0);
    tach_ = &addInput(bus::topics::kWheelTach);
    coil_window_ = &addFeedbackInput(bus::topics::kCoilWindow);
  }
}

void EstimatorNode::stepS0(const bus::StepContext& ctx, const msg::GyroReading& gyro,
                           const msg::SunSensorReading& sun, const ReferenceVectors& reference) {
  const auto tach = tach_->at(ctx.step);
  S0EstimatorInput in;
  in.wheel_speed_rad_s = bus::vec4(tach.wheel_speed_rad_s());
  in.tach_valid = tach.valid();
  in.w_B_rad_s = bus::vec3(gyro.w_body_rad_s());
  in.gyro_valid = gyro.valid();
  in.sun_B_unit = bus::vec3(sun.sun_body_unit());
  in.sun_valid = sun.valid();
  const double jd_tt = jd_epoch_utc_ + (sim::toSeconds(ctx.sim_time_ns) + sim::kTtMinusUtc_s) / 86400.0;
  in.R_SE_N = sim::R_N_SunEcliptic(reference.sun_N_unit, jd_tt).transpose();
  in.b_N_ref_T = reference.b_N_T;
  if (const auto window = coil_window_->atIfAny(ctx.step)) {
    if (window->phase() == msg::CoilWindowPhase::COIL_DONE) {
      in.completed = std::make_pair(
          window->request_id(),
          S0Window{window->t0_ns(), window->t1_ns(), window->pulse_end_ns(), window->t2_ns(),
                   bus::vec3(window->m_body_Am2())});
    } else if (window->phase() == msg::CoilWindowPhase::COIL_REFUSED) {
      in.refused = window->request_id();
    }
  }
  const auto out = s0_->step(in, ctx.sim_time_ns);

  msg::CoilRequest request;
  request.header(bus::makeHeader(ctx, name()));
  if (out.request) {
    request.request_id(out.request->id);
    bus::put(request.m_body_Am2(), out.request->m_B_Am2);
    request.quiet_s(out.request->quiet_s);
    request.pulse_s(out.request->pulse_s);
    request.quiet_after_s(out.request->quiet_after_s);
  }
  coil_request_.write(request);

  msg::FieldEstimate field;
  field.header(bus::makeHeader(ctx, name()));
  bus::put(field.b_body_T(), out.b_B_T);
  field.valid(out.valid);
  field.roll_rad(out.alpha_rad);
  field.cycles(out.cycles);
  field.failed_cycles(out.failed_cycles);
  bus::put(field.b_cycle_body_T(), out.b_cycle_B_T);
  field.t_cycle_ns(out.t_cycle_ns);
  field.along_dipole_Nm(out.along_dipole_Nm);
  field_estimate_.write(field);
}

void EstimatorNode::step(const bus::StepContext& ctx) {
  std::optional<msg::MagnetometerReading> magnetometer;
  if (magnetometer_ != nullptr) magnetometer = magnetometer_->at(ctx.step);
  const auto gyro = gyro_.at(ctx.step);
  const auto& used = last_gyro_.update(gyro);
  const auto reference = reference_.step(ctx.sim_time_ns);
  const auto sun = sun_.at(ctx.step);
  if (s0_) {
    stepS0(ctx, used, sun, reference);
  } else {
    msg::CoilRequest none;
    none.header(bus::makeHeader(ctx, name()));
    coil_request_.write(none);
    msg::FieldEstimate invalid;
    invalid.header(bus::makeHeader(ctx, name()));
    field_estimate_.write(invalid);
  }
  const auto in = toInput(used, sun, magnetometer, reference);
  auto message = toMessage(filter_.step(in, ctx.sim_time_ns));
  message.header(bus::makeHeader(ctx, name()));
  estimate_.write(message);
}

EstimatorNodeParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                               bus::ConfigProblems& problems) {
  bus::ConfigProblems reported_by_dynamics_server;
  const auto plant = sim::readPlant(scenario, reported_by_dynamics_server);
  EstimatorNodeParams p;
  // The onboard models mirror the plant's (an onboard computer carries the same
  // IGRF and propagator; its orbit knowledge is the scenario's initial elements).
  p.reference = {plant.epoch, plant.orbit, plant.orbit_track, plant.field, std::nullopt};
  if (plant.field_model == sim::FieldModel::kSphericalHarmonics) {
    auto harmonics = plant.field_harmonics;
    harmonics.degree = std::min(harmonics.degree, plant.field_degree);
    p.reference.field_harmonics = harmonics;
  }
  if (plant.atmosphere) p.reference.orbit_track.forces.atmosphere = *plant.atmosphere;
  p.jd_epoch_utc = sim::julianDate(plant.epoch);
  auto r = scenario.componentParams(args.name, problems);
  if (r.has("s0")) {
    auto s0 = r.section("s0");
    bool enabled = false;
    s0.read("enabled", enabled);
    S0EstimatorParams q;
    q.wheels = {plant.body.wheel_count, plant.body.wheel_axes_B, plant.body.wheel_inertia_kg_m2};
    s0.read("quiet_s", q.quiet_s, "s");
    s0.read("pulse_s", q.pulse_s, "s");
    s0.read("settle_s", q.settle_s, "s");
    s0.read("quiet_after_s", q.quiet_after_s, "s");
    s0.read("dipole_Am2", q.dipole_Am2, "A m^2");
    s0.read("cycle_period_s", q.cycle_period_s, "s");
    s0.read("average_s", q.average_s, "s");
    s0.read("alternate_sign", q.alternate_sign);
    s0.read("unloading_sign", q.unloading_sign);
    s0.read("max_sun_offset_rad", q.max_sun_offset_rad, "rad");
    bool total_momentum = false;
    s0.read("total_momentum", total_momentum);
    if (total_momentum) q.body_inertia_kg_m2 = plant.body.J_B_kg_m2;
    s0.problems(q.validate());
    if (q.dipole_Am2 > plant.torquer_max_dipole_Am2.x()) {
      s0.problem("dipole_Am2", "exceeds the x coil's limit (spacecraft.torquers.max_dipole_Am2)");
    }
    s0.finish();
    if (enabled) p.s0 = q;
  }
  r.read("kp_per_s", p.filter.kp_per_s, "1/s");
  r.read("ki_per_s2", p.filter.ki_per_s2, "1/s^2");
  r.read("max_bias_rad_s", p.filter.max_bias_rad_s, "rad/s");
  r.read("use_magnetometer", p.filter.use_magnetometer);
  p.filter.sun_only_init = !scenario.hasComponent("magnetometer");
  r.problems(p.filter.validate());
  r.finish();
  return p;
}

}  // namespace flatsat::estimator
