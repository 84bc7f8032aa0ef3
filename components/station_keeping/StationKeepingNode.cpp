// SPDX-License-Identifier: Apache-2.0
#include "components/station_keeping/StationKeepingNode.hpp"

#include <cmath>
#include <memory>

#include <spdlog/spdlog.h>

#include "bus/Convert.hpp"
#include "bus/Stamp.hpp"
#include "components/Processes.hpp"
#include "sim/Constants.hpp"
#include "vehicle/VehicleReader.hpp"
#include "sim/SunEphemeris.hpp"
#include "sim/Time.hpp"

namespace flatsat::station_keeping {

namespace {

constexpr std::size_t kMaxPlanFirings = 8;  // StationKeepingPlan's arrays

/// Thruster `index` of spacecraft.thrusters: the seed's six in numbering order.
GeoThruster thrusterAt(int index) { return kGeoThrusters.at(static_cast<std::size_t>(index)); }

msg::StationKeepingPlan toMessage(const StationKeepingPlan& plan, const SynchronousElements& mean,
                                  PairFailure failure) {
  msg::StationKeepingPlan m;
  m.failure(static_cast<std::uint8_t>(failure));
  m.winter_spring(plan.season.winter_spring);
  m.eclipse(static_cast<std::uint8_t>(plan.season.eclipse));
  m.mean_longitude_rad(mean.longitude_rad);
  m.mean_drift_rad_s(mean.drift_rad_s);
  m.mean_e({mean.e.x(), mean.e.y()});
  m.mean_i_rad({mean.i.x(), mean.i.y()});
  const std::size_t n = std::min(plan.firings.size(), kMaxPlanFirings);
  m.firing_count(static_cast<std::uint32_t>(n));
  for (std::size_t k = 0; k < n; ++k) {
    const PlannedFiring& f = plan.firings[k];
    m.thruster()[k] = static_cast<std::uint8_t>(f.thruster);
    m.ra_rad()[k] = f.ra_rad;
    m.duration_s()[k] = f.duration_s;
    m.dv_m_s()[k] = f.dv_m_s;
    m.job()[k] = static_cast<std::uint8_t>(f.job);
  }
  m.dv_total_m_s(plan.dv_total_m_s);
  return m;
}

}  // namespace

StationKeepingNode::StationKeepingNode(bus::Bus& bus, bus::NodeOptions options,
                                       const StationKeepingNodeParams& params)
    : Component(bus, std::move(options)),
      params_(params),
      planner_(params.planner),
      filter_(params.mean_elements),
      failures_(params.failures) {
  fault_commands_ = std::make_unique<bus::ReaderOf<bus::topics::kFaultCmd>>(
      bus, bus::topics::kFaultCmd, [this](const msg::FaultCmd& command) {
        if (bus::text(command.target()) != "dynamics_server" || bus::text(command.kind()) != "thruster_failed") {
          return;
        }
        if (command.channel() < 0 || command.channel() >= static_cast<int>(kGeoThrusters.size())) {
          spdlog::warn("{}: thruster_failed on channel {}: not one of the six thrusters; the plan keeps its state",
                       name(), command.channel());
          return;
        }
        const std::lock_guard lock(failures_mutex_);
        failures_.push_back({thrusterAt(command.channel()), command.start_ns(), command.duration_ns()});
      });
}

PairFailure StationKeepingNode::failureAt(std::int64_t sim_time_ns) {
  const std::lock_guard lock(failures_mutex_);
  for (const auto& f : failures_) {
    const bool active = sim_time_ns >= f.start_ns && (f.duration_ns == 0 || sim_time_ns < f.start_ns + f.duration_ns);
    if (active) return failureOf(f.thruster);
  }
  return PairFailure::kNone;
}

void StationKeepingNode::step(const bus::StepContext& ctx) {
  const auto truth = truth_.at(ctx.step);
  const double t_s = 1e-9 * static_cast<double>(ctx.sim_time_ns);
  const double jd = params_.jd_epoch + t_s / 86400.0;
  const Eigen::Vector3d r = bus::vec3(truth.r_inertial_m()), v = bus::vec3(truth.v_inertial_m_s());
  const double ra = std::atan2(r.y(), r.x());
  // The last step's thrust, as the orbit determination knows its own
  // manoeuvres: the filter counts it from the orbit before it on.
  const Eigen::Vector3d f_B = bus::vec3(truth.f_thruster_body_N());
  if (!f_B.isZero(0.0)) {
    const Eigen::Vector3d dv_N = bus::quat(truth.q_inertial_body()) * f_B * params_.step_s / params_.planner.mass_kg;
    filter_.impulse(impulseEffect(R_N_orbital(r, v).transpose() * dv_N, ra, v.norm(), sim::kEarthRotationRate_rad_s),
                    t_s - 0.5 * params_.step_s);
  }
  const PairFailure failure = failureAt(ctx.sim_time_ns);
  if (const auto mean = filter_.step(synchronousElements(r, v, sim::gmst_rad(jd)), t_s)) {
    StationKeepingInputs in;
    in.mean = *mean;
    in.failure = failure;
    in.sun_N_unit = sim::sunPosition_N_m(jd).normalized();
    in.dump_dv_m_s = params_.dump_dv_m_s;
    plan_ = planner_.step(in);
    mean_ = *mean;
    ++plan_count_;
    plan_step_ = ctx.step;
    spdlog::debug("{}: plan {} ({}): {} firings, {:.3f} m/s", name(), plan_count_, nameOf(failure),
                  plan_->firings.size(), plan_->dv_total_m_s);
  }
  msg::StationKeepingPlan message = plan_ ? toMessage(*plan_, mean_, failure) : msg::StationKeepingPlan{};
  message.failure(static_cast<std::uint8_t>(failure));
  message.plan_count(plan_count_);
  message.plan_step(plan_step_);
  bus::stamp(message.header(), ctx, name());
  plan_out_.write(message);
}

StationKeepingNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                    const bus::NodeArgs& args, bus::ConfigProblems& problems) {
  const vehicle::VehicleDescription& known = vehicle.onboard;  // flight software sees only this
  StationKeepingNodeParams p;
  p.jd_epoch = sim::julianDate(known.epoch);
  p.step_s = scenario.componentStep_s(args.name);
  auto r = scenario.componentParams(args.name, problems);
  StationKeepingParams& k = p.planner;
  vehicle::refuseMovedKeys(r, {{"station_longitude_rad", "orbit.station_longitude_deg"}});
  if (known.station_longitude_rad) {
    k.station_longitude_rad = *known.station_longitude_rad;
  } else {
    r.problem("", "needs a slot to hold: orbit.station_longitude_deg");
  }
  r.read("longitude_return_s", k.longitude_return_s, "s");
  r.read("drift_horizon_s", k.drift_horizon_s, "s");
  r.read("max_burn_s", k.max_burn_s, "s");
  r.read("max_ra_shift_rad", k.max_ra_shift_rad, "rad");
  r.read("dump_arc_rad", k.dump_arc_rad, "rad");
  r.read("box_longitude_rad", k.box_longitude_rad, "rad");
  r.read("box_inclination_rad", k.box_inclination_rad, "rad");
  r.read("box_eccentricity", k.box_eccentricity, "-");
  std::string centre_pair = "independent";
  r.read("centre_pair", centre_pair);
  if (centre_pair == "equal") {
    k.centre_pair_equal = true;
  } else if (centre_pair != "independent") {
    r.problem("centre_pair", "'" + centre_pair + "' is neither equal (the seed's) nor independent");
  }
  r.read("cant_rad", k.thrusters.cant_rad, "rad");
  r.read("slew_rad", k.thrusters.slew_rad, "rad");
  r.read("mean_elements_window_s", p.mean_elements.window_s, "s");
  r.read("dump_dv_m_s", p.dump_dv_m_s, "m/s");
  if (!(p.dump_dv_m_s >= 0.0 && p.dump_dv_m_s <= 1.0)) r.problem("dump_dv_m_s", "outside [0, 1] m/s");
  k.mass_kg = known.orbit_track.forces.mass_kg;
  // The plant's thrusters must be the seed's six, in numbering order, with the
  // cant and slew the plan assumes (thrust lines through the CM).
  if (known.thrusters.size() != kGeoThrusters.size()) {
    r.problem("", "needs spacecraft.thrusters to be the seed's six (NW, NC, NE, SW, SC, SE), not " +
                      std::to_string(known.thrusters.size()));
  } else if (validate(k.thrusters).empty()) {
    k.thrust_N = known.thrusters.front().thrust_N;
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector3d expected = forceDirection_orbital(thrusterAt(i), k.thrusters);
      if ((known.thrusters[i].direction_B - expected).norm() > 1e-3) {
        r.problem("cant_rad", "spacecraft.thrusters[" + std::to_string(i) + "] is not " + nameOf(thrusterAt(i)) +
                                  " at this cant and slew (force direction east, north, zenith expected " +
                                  std::to_string(expected.x()) + ", " + std::to_string(expected.y()) + ", " +
                                  std::to_string(expected.z()) + ")");
      }
      if (known.thrusters[i].thrust_N != k.thrust_N) {
        r.problem("", "spacecraft.thrusters[" + std::to_string(i) + "]: the six must have one thrust_N");
      }
    }
  }
  // The failures fault management has declared (the truth's unless onboard.faults says otherwise).
  for (const auto& fault : known.faults) {
    if (fault.kind != sim::ActuatorFaultKind::kThrusterFailed) continue;
    if (fault.channel < 0 || fault.channel >= static_cast<int>(kGeoThrusters.size())) {
      r.problem("", "spacecraft.faults: thruster_failed on channel " + std::to_string(fault.channel) +
                        " takes out more than one power-unit pair (Table I has rows for one)");
      continue;
    }
    p.failures.push_back({thrusterAt(fault.channel), fault.start_ns, fault.duration_ns});
  }
  r.problems(validate(k));
  r.problems(validate(p.mean_elements));
  r.finish();
  return p;
}

int runProcess(int argc, char** argv) {
  return bus::runNodeOf<StationKeepingNode>(argc, argv, "station_keeping", vehicle::withVehicle(readParams));
}

}  // namespace flatsat::station_keeping
