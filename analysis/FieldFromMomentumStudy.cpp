// SPDX-License-Identifier: Apache-2.0
#include "analysis/FieldFromMomentumStudy.hpp"

#include <cmath>
#include <cstdio>
#include <deque>
#include <optional>

#include "bus/Scenario.hpp"
#include "components/attitude_controller/AttitudeControllerNode.hpp"
#include "components/estimator/EstimatorNode.hpp"
#include "components/estimator/FieldFromMomentumEstimator.hpp"
#include "components/gyro/GyroNode.hpp"
#include "components/sun_sensor/SunSensorNode.hpp"
#include "components/wheel_tach/WheelTachNode.hpp"
#include "sim/DynamicsModel.hpp"
#include "sim/Frames.hpp"
#include "analysis/Conventions.hpp"
#include "components/dynamics_server/DynamicsServerParams.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::analysis {

namespace {

struct Setup {
  sim::DynamicsParams plant;
  vehicle::VehicleDescription onboard;  // what the estimator knows of the wheels and the body
  std::int64_t step_ns;
  double orbit_period_s;
  attitude_controller::SunPointingControllerParams controller;
  wheel_tach::WheelTachParams tach;
  gyro::GyroParams gyro;
  sun_sensor::SunSensorParams sun_sensor;  // the Sun the estimator is given is sensed
  onboard::ReferenceModelParams reference;  // the estimator's: the onboard view's orbit, field model, Sun
  double jd_epoch;
};

/// How the momentum and the intervals are taken.
struct Form {
  const char* name;
  bool total_momentum;  // wheels + J ω (gyro), else wheels only
  double settle_s;      // quiet after the pulse counted with it
  bool quiet_after;     // a quiet interval as long as the pulse after settling
};
constexpr Form kForms[] = {
    {"seed", false, 0.0, false},          // the seed's closed form as written
    {"settle", false, 60.0, false},       // + the attitude loop's settling counted
    {"settle+q", false, 60.0, true},      // + a changing disturbance measured after
    {"total+q", true, 0.0, true},         // body momentum from the gyro instead of settling
};

struct Case {
  Form form;
  double window_s;   // Δt1 = pulse (= quiet after)
  double dipole_Am2;
};

struct Stats {
  double sum2 = 0.0, max = 0.0;
  int n = 0;
  void add(double v) {
    sum2 += v * v;
    max = std::max(max, std::abs(v));
    ++n;
  }
  double rms() const { return n ? std::sqrt(sum2 / n) : NAN; }
};

double wrap(double a) { return std::remainder(a, 2.0 * 3.14159265358979323846); }

double julianTt(const Setup& s, std::int64_t t_ns) {
  return s.jd_epoch + (static_cast<double>(t_ns) * 1e-9 + sim::kTtMinusUtc_s) / 86400.0;
}

/// [rad] The true roll about the Sun line: body y in the Sun-ecliptic frame.
double trueRoll(const sim::Truth& truth, const Eigen::Matrix3d& R_N_SE) {
  const Eigen::Vector3d y_SE = R_N_SE.transpose() * (truth.q_NB * Eigen::Vector3d::UnitY());
  return std::atan2(y_SE.z(), y_SE.y());
}

Setup readSetup(const std::string& file) {
  const bus::Scenario scenario = bus::loadScenario(file);
  bus::ConfigProblems problems;
  const vehicle::Vehicle craft = vehicle::readVehicle(scenario, problems);
  const auto server = dynamics_server::readParams(scenario, craft, {scenario.file, "dynamics_server", ""}, problems);
  Setup s{server.dynamics, craft.onboard, server.step_period_ns, server.orbit_period_s,
          attitude_controller::readParams(scenario, craft, {file, "attitude_controller", ""}, problems).law,
          wheel_tach::readParams(scenario, craft, {file, "wheel_tach", ""}, problems).model,
          gyro::readParams(scenario, {file, "gyro", ""}, problems).model,
          sun_sensor::readParams(scenario, craft, {file, "sun_sensor", ""}, problems).model,
          estimator::readParams(scenario, craft, {file, "estimator", ""}, problems).reference,
          sim::julianDate(server.dynamics.epoch)};
  if (!problems.empty()) throw std::runtime_error(problems.joined());
  // Start on the Sun with a roll of 30 deg: the study is about holding, not acquiring.
  const sim::DynamicsModel probe(s.plant);
  const Eigen::Matrix3d R_N_SE = sim::R_N_SunEcliptic(probe.truth().sun_N_unit, julianTt(s, 0));
  const double roll = 30.0 / kRadToDeg;
  Eigen::Matrix3d R_NB;
  R_NB.col(0) = R_N_SE.col(0);
  R_NB.col(1) = std::cos(roll) * R_N_SE.col(1) + std::sin(roll) * R_N_SE.col(2);
  R_NB.col(2) = R_NB.col(0).cross(R_NB.col(1));
  s.plant.q0_NB = Eigen::Quaterniond(R_NB);
  s.plant.w0_NB_B_rad_s.setZero();
  return s;
}

struct Result {
  Stats field_cycle_pct, alpha_cycle_deg, field_pct, alpha_deg;
  int cycles = 0, failed = 0;
};

Result runCase(const Setup& s, const Case& c, const FieldFromMomentumStudyOptions& o) {
  sim::DynamicsModel model(s.plant);
  attitude_controller::SunPointingController controller(s.controller);
  wheel_tach::WheelTachModel tach(s.tach);
  gyro::GyroModel gyro(s.gyro);
  sun_sensor::SunSensorModel sun_sensor(s.sun_sensor);
  onboard::ReferenceModel reference(s.reference);
  estimator::FieldFromMomentumParams p;
  p.wheels = wheelGeometryOf(s.onboard.body);
  p.quiet_s = p.pulse_s = c.window_s;
  p.settle_s = c.form.settle_s;
  p.quiet_after_s = c.form.quiet_after ? c.window_s : 0.0;
  if (c.form.total_momentum) p.body_inertia_kg_m2 = s.onboard.body.J_B_kg_m2;
  p.dipole_Am2 = c.dipole_Am2;
  p.cycle_period_s = std::max(o.cycle_s, 3 * c.window_s + c.form.settle_s);
  p.average_s = std::min(2.0, c.window_s / 4);
  estimator::FieldFromMomentumEstimator s0(p);

  struct Past {
    std::int64_t t_ns;
    Eigen::Vector3d b_B_T;
    Eigen::Vector3d b_SE_T;
    double roll;
  };
  std::deque<Past> past;  // truth over the last cycle, to judge a window at its t_ref
  std::optional<std::pair<std::uint32_t, estimator::DipoleWindow>> window;
  Result r;
  const auto end_ns = static_cast<std::int64_t>(o.orbits * s.orbit_period_s * 1e9);
  const auto ns = [](double sec) { return static_cast<std::int64_t>(std::llround(sec * 1e9)); };
  for (std::int64_t t = 0; t <= end_ns; t += s.step_ns) {
    const sim::Truth& truth = model.truth();
    const Eigen::Matrix3d R_N_SE = sim::R_N_SunEcliptic(truth.sun_N_unit, julianTt(s, t));
    past.push_back({t, truth.b_B_T, R_N_SE.transpose() * truth.b_N_T, trueRoll(truth, R_N_SE)});
    while (past.front().t_ns < t - ns(o.cycle_s + 4 * c.window_s + c.form.settle_s)) past.pop_front();

    const auto speeds = tach.step({truth.wheel_speed_rad_s}, t).wheel_speed_rad_s;
    estimator::FieldFromMomentumInput in;
    in.wheel_speed_rad_s = speeds;
    in.tach_valid = true;
    in.w_B_rad_s = gyro.step({truth.w_NB_B_rad_s}, t).w_NB_B_rad_s;
    in.gyro_valid = true;
    // What the rig's estimator is given: the sensed Sun, and the onboard view's
    // field and Sun at its own orbit knowledge (by default the truth's models).
    const auto sensed = sun_sensor.step({truth.sun_B_unit, truth.illumination,
                                         truth.solar_flux_W_m2 / sim::kSolarFlux1Au_W_m2,
                                         truth.q_NB.conjugate() * truth.r_N_m},
                                        t);
    const auto known = reference.step(t);
    in.sun_B_unit = sensed.sun_B_unit;
    in.sun_valid = sensed.valid;
    in.R_SE_N = sim::R_N_SunEcliptic(known.sun_N_unit, julianTt(s, t)).transpose();
    in.b_N_ref_T = known.b_N_T;
    if (window && window->second.t2_ns == t) {
      in.completed = window;
      window.reset();
    }
    const auto out = s0.step(in, t);
    if (out.solved_now) {
      const Past* at = &past.front();
      for (const auto& each : past) {
        if (std::llabs(each.t_ns - out.t_cycle_ns) < std::llabs(at->t_ns - out.t_cycle_ns)) at = &each;
      }
      r.field_cycle_pct.add(100.0 * (out.b_cycle_B_T.tail<2>() - at->b_B_T.tail<2>()).norm() /
                            at->b_B_T.norm());
      const double alpha = estimator::s0RollAngle(out.b_cycle_B_T.y(), out.b_cycle_B_T.z(),
                                                   at->b_SE_T.y(), at->b_SE_T.z());
      r.alpha_cycle_deg.add(wrap(alpha - at->roll) * kRadToDeg);
    }
    if (out.valid) {
      r.field_pct.add(100.0 * (out.b_B_T - truth.b_B_T).norm() / truth.b_B_T.norm());
      r.alpha_deg.add(wrap(out.alpha_rad - past.back().roll) * kRadToDeg);
    }
    if (out.request && !window) {
      estimator::DipoleWindow w;
      w.t0_ns = t;
      w.t1_ns = t + ns(out.request->quiet_s);
      w.pulse_end_ns = w.t1_ns + ns(out.request->pulse_s);
      w.t2_ns = w.pulse_end_ns + ns(out.request->quiet_after_s);
      w.m_B_Am2 = out.request->m_B_Am2;
      window = std::make_pair(out.request->id, w);
    }
    attitude_controller::SunPointingControllerInput ci;
    ci.sun_B_est_unit = truth.sun_B_unit;
    ci.w_NB_B_rad_s = truth.w_NB_B_rad_s;
    ci.wheel_speed_rad_s = speeds;
    ci.valid = true;
    sim::ActuatorCommands cmd;
    cmd.wheel_torque_Nm = controller.step(ci, t).wheel_torque_Nm;
    if (window && t >= window->second.t1_ns && t < window->second.pulse_end_ns) {
      cmd.dipole_B_Am2 = window->second.m_B_Am2;
    }
    model.step(cmd, t + s.step_ns);
    r.cycles = static_cast<int>(out.cycles);
    r.failed = static_cast<int>(out.failed_cycles);
  }
  return r;
}

}  // namespace

int runFieldFromMomentumStudy(const FieldFromMomentumStudyOptions& o) {
  const Setup setup = readSetup(o.scenario);
  std::printf("# S0 accuracy: %s, %.1f orbit(s) per case, a window every %.0f s\n",
              o.scenario.c_str(), o.orbits, o.cycle_s);
  std::printf("# attitude loop kp %.3g Nm/rad kd %.3g Nms/rad; tachometers noise %.3g rad/s, quantum %.3g rad/s\n",
              setup.controller.kp_Nm_per_rad, setup.controller.kd_Nm_s_per_rad,
              setup.tach.noise_rad_s, setup.tach.quantum_rad_s);
  std::printf("# errors per window (By, Bz at the pulse's mid-time) and all along (α carried by the gyro)\n");
  std::printf("# forms: seed = wheel momentum, quiet + pulse (the seed's closed form); settle = + 60 s after\n"
              "# the pulse for the attitude loop; settle+q = + a quiet interval after (a linearly changing\n"
              "# disturbance drops out); total+q = wheels + J w from the gyro, quiet + pulse + quiet\n");
  std::printf("%9s %8s %10s %6s %6s %12s %12s %12s %12s %12s\n", "form", "dt1_s", "dipole_Am2",
              "cycles", "failed", "field_pct_rms", "field_pct_max", "alpha_deg_rms", "alpha_deg_max",
              "field_all_pct_rms");
  const auto row = [&](const Form& form, double window, double dipole) {
    const Result r = runCase(setup, {form, window, dipole}, o);
    std::printf("%9s %8.0f %10.0f %6d %6d %12.3f %12.3f %12.3f %12.3f %12.3f\n", form.name, window,
                dipole, r.cycles, r.failed, r.field_cycle_pct.rms(), r.field_cycle_pct.max,
                r.alpha_cycle_deg.rms(), r.alpha_cycle_deg.max, r.field_pct.rms());
    std::fflush(stdout);
  };
  if (!o.form.empty()) {
    for (const Form& form : kForms) {
      if (o.form == form.name) {
        row(form, o.window_s, o.dipole_Am2);
        return 0;
      }
    }
    std::fprintf(stderr, "study s0: --form %s: must be seed, settle, settle+q or total+q\n", o.form.c_str());
    return kExitBadInput;
  }
  for (const Form& form : kForms) {
    for (const double window : {1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 60.0}) {
      for (const double dipole : {25.0, 50.0, 100.0, 150.0}) row(form, window, dipole);
    }
  }
  return 0;
}

}  // namespace flatsat::analysis
