// SPDX-License-Identifier: Apache-2.0
#include "components/estimator/EstimatorNode.hpp"

#include <algorithm>

#include "bus/Convert.hpp"
#include "components/Processes.hpp"
#include "components/common/StateJson.hpp"
#include "components/common/onboard/ReferenceParams.hpp"
#include "sim/Frames.hpp"
#include "sim/Time.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::estimator {

namespace {

/// The vector measurements of one step, whichever sensors the rig has.
struct Vectors {
  Eigen::Vector3d sun_B_unit = Eigen::Vector3d::Zero();
  bool sun_valid = false;
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();
  bool b_valid = false;
};

Vectors toVectors(const std::optional<msg::SunSensorReading>& sun,
                  const std::optional<msg::MagnetometerReading>& magnetometer) {
  Vectors v;
  if (sun) {
    v.sun_B_unit = bus::vec3(sun->sun_body_unit());
    v.sun_valid = sun->valid();
  }
  if (magnetometer) {
    v.b_B_T = bus::vec3(magnetometer->b_body_T());
    v.b_valid = magnetometer->valid() && !magnetometer->saturated();
  }
  return v;
}

/// "ok", "lost" (no usable sample this step: eclipse, dropout, saturation, late or lost on the bus) or "none".
const char* sensorState(bool present, bool valid) {
  if (!present) return "none";
  return valid ? "ok" : "lost";
}

template <class Array>
void putBlock(Array& out, const Eigen::Matrix3d& block) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out[static_cast<std::size_t>(3 * r + c)] = block(r, c);
  }
}

/// The fields both filters' outputs share.
template <class Output>
msg::AttitudeEstimate commonFields(const Output& out) {
  msg::AttitudeEstimate m;
  bus::put(m.q_inertial_body(), out.q_NB);
  bus::put(m.w_body_rad_s(), out.w_NB_B_rad_s);
  bus::put(m.gyro_bias_body_rad_s(), out.gyro_bias_B_rad_s);
  bus::put(m.sun_body_unit(), out.sun_B_est_unit);
  m.initialized(out.initialized);
  return m;
}

msg::AttitudeEstimate toMessage(const AttitudeEstimatorOutput& out) {
  msg::AttitudeEstimate m = commonFields(out);
  m.sun_used(out.sun_used);
  m.field_used(out.field_used);
  m.valid(out.initialized && out.q_NB.coeffs().allFinite() && out.w_NB_B_rad_s.allFinite());
  return m;
}

msg::AttitudeEstimate toMessage(const MekfOutput& out) {
  msg::AttitudeEstimate m = commonFields(out);
  m.sun_used(out.sun == MeasurementUse::kUsed);
  m.field_used(out.field == MeasurementUse::kUsed);
  m.valid(out.valid);
  m.has_covariance(true);
  putBlock(m.attitude_cov_body_rad2(), out.covariance.topLeftCorner<3, 3>());
  putBlock(m.gyro_bias_cov_body_rad2_s2(), out.covariance.block<3, 3>(3, 3));
  putBlock(m.attitude_bias_cov_body_rad2_s(), out.covariance.block<3, 3>(0, 3));
  m.measurements_rejected(out.rejected_total);
  return m;
}

}  // namespace

EstimatorNode::EstimatorNode(bus::Bus& bus, bus::NodeOptions options,
                             const EstimatorNodeParams& params)
    : Component(bus, std::move(options)),
      reference_(params.reference),
      use_magnetometer_(params.filter.use_magnetometer),
      jd_epoch_utc_(params.jd_epoch_utc) {
  if (params.method == EstimatorMethod::kMekf) {
    mekf_.emplace(params.mekf);
  } else {
    mahony_.emplace(params.filter);
  }
  if (options_.schedule.count(std::string(bus::topics::kSunSensor.producer))) {
    sun_ = &addInput(bus::topics::kSunSensor);
  }
  if (options_.schedule.count(std::string(bus::topics::kMagnetometer.producer))) {
    magnetometer_ = &addInput(bus::topics::kMagnetometer);
  }
  if (mekf_ && options_.schedule.count(std::string(bus::topics::kStarTracker.producer))) {
    star_tracker_ = &addInput(bus::topics::kStarTracker);
  }
  if (params.s0) {
    s0_.emplace(*params.s0);
    tach_ = &addInput(bus::topics::kWheelTach);
    coil_window_ = &addFeedbackInput(bus::topics::kCoilWindow);
  }
}

void EstimatorNode::stepFieldFromMomentum(const bus::StepContext& ctx, const msg::GyroReading& gyro,
                           const Eigen::Vector3d& sun_B_unit, bool sun_valid,
                           const onboard::ReferenceVectors& reference) {
  const auto tach = tach_->at(ctx.step);
  FieldFromMomentumInput in;
  in.wheel_speed_rad_s = bus::vec4(tach.wheel_speed_rad_s());
  in.tach_valid = tach.valid();
  in.w_B_rad_s = bus::vec3(gyro.w_body_rad_s());
  in.gyro_valid = gyro.valid();
  in.sun_B_unit = sun_B_unit;
  in.sun_valid = sun_valid;
  const double jd_tt = jd_epoch_utc_ + (sim::toSeconds(ctx.sim_time_ns) + sim::kTtMinusUtc_s) / 86400.0;
  in.R_SE_N = sim::R_N_SunEcliptic(reference.sun_N_unit, jd_tt).transpose();
  in.b_N_ref_T = reference.b_N_T;
  if (const auto window = coil_window_->atIfAny(ctx.step)) {
    if (window->phase() == msg::CoilWindowPhase::COIL_DONE) {
      in.completed = std::make_pair(
          window->request_id(),
          DipoleWindow{window->t0_ns(), window->t1_ns(), window->pulse_end_ns(), window->t2_ns(),
                   bus::vec3(window->m_body_Am2())});
    } else if (window->phase() == msg::CoilWindowPhase::COIL_REFUSED) {
      in.refused = window->request_id();
    }
  }
  const auto out = s0_->step(in, ctx.sim_time_ns);

  msg::CoilRequest request;
  bus::stamp(request.header(), ctx, name());
  if (out.request) {
    request.request_id(out.request->id);
    bus::put(request.m_body_Am2(), out.request->m_B_Am2);
    request.quiet_s(out.request->quiet_s);
    request.pulse_s(out.request->pulse_s);
    request.quiet_after_s(out.request->quiet_after_s);
    request.law_pulse_min_Am2(out.request->law_pulse_min_Am2);
  }
  coil_request_.write(request);

  msg::FieldEstimate field;
  bus::stamp(field.header(), ctx, name());
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

nlohmann::json EstimatorNode::saveState() const {
  nlohmann::json j;
  if (mekf_) {
    const MekfState s = mekf_->state();
    j["mekf"] = {{"q_inertial_body", state_json::quaternion(s.q_NB)},
                 {"gyro_bias_body_rad_s", state_json::matrix(s.bias_B_rad_s)},
                 {"magnetometer_bias_body_T", state_json::matrix(s.mag_bias_B_T)},
                 {"covariance", state_json::matrix(s.P)},
                 {"initialized", s.initialized},
                 {"measurements_rejected", s.rejected_total},
                 {"rejected_in_a_row", s.rejected_in_a_row},
                 {"last_t_ns", s.last_t_ns},
                 {"has_last_t", s.has_last_t}};
    if (previous_w_B_rad_s_) j["previous_w_body_rad_s"] = state_json::matrix(*previous_w_B_rad_s_);
  } else {
    const AttitudeEstimatorState s = mahony_->state();
    j["mahony"] = {{"q_inertial_body", state_json::quaternion(s.q_NB)},
                   {"gyro_bias_body_rad_s", state_json::matrix(s.bias_B_rad_s)},
                   {"initialized", s.initialized},
                   {"last_t_ns", s.last_t_ns},
                   {"has_last_t", s.has_last_t}};
  }
  return j;
}

void EstimatorNode::restoreState(const nlohmann::json& j) {
  if (mekf_) {
    const auto& m = j.at("mekf");
    MekfState s;
    s.q_NB = state_json::readQuaternion(m, "q_inertial_body");
    state_json::read(m, "gyro_bias_body_rad_s", s.bias_B_rad_s);
    state_json::read(m, "magnetometer_bias_body_T", s.mag_bias_B_T);
    state_json::read(m, "covariance", s.P);
    s.initialized = m.at("initialized").get<bool>();
    s.rejected_total = m.at("measurements_rejected").get<std::uint64_t>();
    s.rejected_in_a_row = m.at("rejected_in_a_row").get<std::array<int, 3>>();
    s.last_t_ns = m.at("last_t_ns").get<std::int64_t>();
    s.has_last_t = m.at("has_last_t").get<bool>();
    if (j.contains("previous_w_body_rad_s")) {
      Eigen::Vector3d w;
      state_json::read(j, "previous_w_body_rad_s", w);
      previous_w_B_rad_s_ = w;
    }
    mekf_->restore(s);
    mekf_initialized_ = s.initialized;
  } else {
    const auto& m = j.at("mahony");
    AttitudeEstimatorState s;
    s.q_NB = state_json::readQuaternion(m, "q_inertial_body");
    state_json::read(m, "gyro_bias_body_rad_s", s.bias_B_rad_s);
    s.initialized = m.at("initialized").get<bool>();
    s.last_t_ns = m.at("last_t_ns").get<std::int64_t>();
    s.has_last_t = m.at("has_last_t").get<bool>();
    mahony_->restore(s);
  }
}

void EstimatorNode::step(const bus::StepContext& ctx) {
  std::optional<msg::SunSensorReading> sun;
  std::optional<msg::MagnetometerReading> magnetometer;
  // A measurement not of this step (lost or late on the bus, or paced and
  // late) is no measurement: correcting with it again would count it twice.
  if (sun_ != nullptr) sun = sun_->dueAt(ctx.step);
  if (magnetometer_ != nullptr) magnetometer = magnetometer_->dueAt(ctx.step);
  const msg::GyroReading gyro_sample = gyro_.at(ctx.step);
  const auto gyro = last_gyro_.update(gyro_sample);
  const Vectors v = toVectors(sun, magnetometer);
  const onboard::ReferenceVectors reference = reference_.step(ctx.sim_time_ns);
  if (s0_) {
    stepFieldFromMomentum(ctx, gyro, v.sun_B_unit, v.sun_valid, reference);
  } else {
    msg::CoilRequest none;
    bus::stamp(none.header(), ctx, name());
    coil_request_.write(none);
    msg::FieldEstimate invalid;
    bus::stamp(invalid.header(), ctx, name());
    field_estimate_.write(invalid);
  }

  msg::AttitudeEstimate message;
  if (mekf_) {
    // The rig's gyro reports the rate at the sample time; the MEKF propagates with the mean
    // rate over the step. With the wheel torque held over each step the rate is piecewise
    // linear, so the trapezoid ½(ω_k−1 + ω_k) is that mean.
    const Eigen::Vector3d w_B = bus::vec3(gyro.w_body_rad_s());
    MekfInput in;
    in.w_gyro_B_rad_s = previous_w_B_rad_s_ ? 0.5 * (*previous_w_B_rad_s_ + w_B) : w_B;
    previous_w_B_rad_s_ = w_B;
    in.sun_B_meas_unit = v.sun_B_unit;
    in.sun_valid = v.sun_valid;
    in.b_B_meas_T = v.b_B_T;
    // Without use_magnetometer the field only initialises the filter (TRIAD), as for Mahony.
    in.b_valid = v.b_valid && (use_magnetometer_ || !mekf_initialized_);
    in.sun_N_ref_unit = reference.sun_N_unit;
    in.b_N_ref_T = reference.b_N_T;
    if (star_tracker_ != nullptr) {
      if (const auto star = star_tracker_->dueAt(ctx.step)) {
        in.q_NB_star = bus::quat(star->q_inertial_body()).normalized();
        in.star_valid = star->valid() && in.q_NB_star.coeffs().allFinite();
      }
      star_valid_ = in.star_valid;
    }
    const MekfOutput out = mekf_->step(in, ctx.sim_time_ns);
    mekf_initialized_ = out.initialized;
    message = toMessage(out);
  } else {
    AttitudeEstimatorInput in;
    in.w_gyro_B_rad_s = bus::vec3(gyro.w_body_rad_s());
    in.sun_B_meas_unit = v.sun_B_unit;
    in.sun_valid = v.sun_valid;
    in.b_B_meas_T = v.b_B_T;
    in.b_valid = v.b_valid;
    in.sun_N_ref_unit = reference.sun_N_unit;
    in.b_N_ref_T = reference.b_N_T;
    message = toMessage(mahony_->step(in, ctx.sim_time_ns));
  }
  bus::stamp(message.header(), ctx, name());
  estimate_.write(message);

  // The status text is built only when a sensor's state changes: building it
  // every step cost more than the Mahony filter (callgrind).
  const unsigned status_bits = unsigned{gyro_sample.valid()} | unsigned{v.sun_valid} << 1U |
                               unsigned{v.b_valid} << 2U | unsigned{star_valid_} << 3U |
                               unsigned{message.valid()} << 4U;
  if (status_bits == status_bits_) return;
  status_bits_ = status_bits;
  std::string status = std::string(mekf_ ? "mekf" : "mahony") +
                       ": gyro " + sensorState(true, gyro_sample.valid()) +
                       ", sun " + sensorState(sun_ != nullptr, v.sun_valid) +
                       ", magnetometer " + sensorState(magnetometer_ != nullptr, v.b_valid);
  if (star_tracker_ != nullptr) status += std::string(", star tracker ") + sensorState(true, star_valid_);
  if (!message.valid()) status += ", estimate INVALID";
  setStatus(status);
}

EstimatorNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                               const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  const vehicle::VehicleDescription& known = vehicle.onboard;  // flight software sees only this
  EstimatorNodeParams p;
  p.jd_epoch_utc = sim::julianDate(known.epoch);
  auto r = scenario.componentParams(args.name, problems);
  vehicle::refuseMovedKeys(r, vehicle::kMovedReferenceKeys);
  std::string method = "mahony";
  r.read("method", method);
  if (method == "mekf") {
    p.method = EstimatorMethod::kMekf;
  } else if (method != "mahony") {
    r.problem("method", "'" + method + "' is not mahony or mekf");
  }
  p.reference = onboard::referenceModelOf(known, onboard::readFieldNodeSpacing(r));
  r.read("use_magnetometer", p.filter.use_magnetometer);
  p.filter.sun_only_init = !scenario.hasComponent("magnetometer");
  r.read("kp_per_s", p.filter.kp_per_s, "1/s");
  r.read("ki_per_s2", p.filter.ki_per_s2, "1/s^2");
  r.read("max_bias_rad_s", p.filter.max_bias_rad_s, "rad/s");
  r.read("gyro_arw_rad_per_sqrt_s", p.mekf.gyro_arw_rad_per_sqrt_s, "-");
  r.read("gyro_rrw_rad_per_s_sqrt_s", p.mekf.gyro_rrw_rad_per_s_sqrt_s, "-");
  r.read("sun_sigma_rad", p.mekf.sun_sigma_rad, "rad");
  r.read("magnetometer_noise_T", p.mekf.magnetometer_noise_T, "T");
  r.read("field_model_sigma_rad", p.mekf.field_model_sigma_rad, "rad");
  r.read("magnetometer_bias_sigma_T", p.mekf.magnetometer_bias_sigma_T, "T");
  r.read("magnetometer_bias_rw_T_per_sqrt_s", p.mekf.magnetometer_bias_rw_T_per_sqrt_s, "-");
  r.read("star_tracker_sigma_body_rad", p.mekf.star_tracker_sigma_B_rad, "rad");
  r.read("initial_attitude_sigma_rad", p.mekf.initial_attitude_sigma_rad, "rad");
  r.read("initial_bias_sigma_rad_s", p.mekf.initial_bias_sigma_rad_s, "rad/s");
  r.read("gate_probability", p.mekf.gate_probability, "-");
  r.read("max_attitude_sigma_rad", p.mekf.max_attitude_sigma_rad, "rad");
  r.read("reacquire_after_rejections", p.mekf.reacquire_after_rejections);
  if (r.has("s0")) {
    auto s0 = r.section("s0");
    bool enabled = false;
    s0.read("enabled", enabled);
    FieldFromMomentumParams q;
    q.wheels = wheelGeometryOf(known.body);
    s0.read("quiet_s", q.quiet_s, "s");
    s0.read("pulse_s", q.pulse_s, "s");
    s0.read("settle_s", q.settle_s, "s");
    s0.read("quiet_after_s", q.quiet_after_s, "s");
    s0.read("dipole_Am2", q.dipole_Am2, "A m^2");
    s0.read("cycle_period_s", q.cycle_period_s, "s");
    s0.read("average_s", q.average_s, "s");
    s0.read("alternate_sign", q.alternate_sign);
    s0.read("unloading_sign", q.unloading_sign);
    s0.read("law_pulse_min_Am2", q.law_pulse_min_Am2, "A m^2");
    s0.read("max_sun_offset_rad", q.max_sun_offset_rad, "rad");
    bool total_momentum = false;
    s0.read("total_momentum", total_momentum);
    if (total_momentum) q.body_inertia_kg_m2 = known.body.J_B_kg_m2;
    s0.problems(q.validate());
    if (q.dipole_Am2 > known.torquer_max_dipole_Am2.x()) {
      s0.problem("dipole_Am2", "exceeds the x coil's limit (spacecraft.torquers.max_dipole_Am2)");
    }
    s0.finish();
    if (enabled) p.s0 = q;
  }
  r.problems(p.method == EstimatorMethod::kMekf ? p.mekf.validate() : p.filter.validate());
  r.finish();
  return p;
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<EstimatorNode>(argc, argv, "estimator", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::estimator
