// SPDX-License-Identifier: Apache-2.0
#include "components/estimator/EstimatorNode.hpp"

#include <optional>

#include "bus/Convert.hpp"
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
    : Component(bus, std::move(options)), filter_(params.filter), reference_(params.reference) {
  if (options_.schedule.count(std::string(bus::topics::kMagnetometer.producer))) {
    magnetometer_ = &addInput(bus::topics::kMagnetometer);
  }
}

void EstimatorNode::step(const bus::StepContext& ctx) {
  std::optional<msg::MagnetometerReading> magnetometer;
  if (magnetometer_ != nullptr) magnetometer = magnetometer_->at(ctx.step);
  const auto gyro = gyro_.at(ctx.step);
  const auto& used = last_gyro_.update(gyro);
  const auto in = toInput(used, sun_.at(ctx.step), magnetometer,
                          reference_.step(ctx.sim_time_ns));
  auto message = toMessage(filter_.step(in, ctx.sim_time_ns));
  message.header(bus::makeHeader(ctx, name()));
  estimate_.write(message);
}

EstimatorNodeParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                               bus::ConfigProblems& problems) {
  bus::ConfigProblems reported_by_dynamics_server;
  const auto plant = sim::readPlant(scenario, reported_by_dynamics_server);
  EstimatorNodeParams p;
  p.reference = {plant.epoch, plant.orbit, plant.field};
  auto r = scenario.componentParams(args.name, problems);
  r.read("kp_per_s", p.filter.kp_per_s, "1/s");
  r.read("ki_per_s2", p.filter.ki_per_s2, "1/s^2");
  r.read("max_bias_rad_s", p.filter.max_bias_rad_s, "rad/s");
  r.read("use_magnetometer", p.filter.use_magnetometer);
  r.problems(p.filter.validate());
  r.finish();
  return p;
}

}  // namespace flatsat::estimator
