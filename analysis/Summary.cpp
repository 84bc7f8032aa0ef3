// SPDX-License-Identifier: Apache-2.0
#include "analysis/Summary.hpp"
#include "analysis/SummaryAngleOnly.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include "bus/Convert.hpp"
#include "bus/Recording.hpp"
#include "bus/RecordingMeta.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "components/attitude_controller/AttitudeControllerNode.hpp"
#include "sim/Frames.hpp"
#include "sim/Time.hpp"
#include "analysis/Conventions.hpp"
#include "analysis/SummaryEstimator.hpp"
#include "analysis/SummaryMagnetic.hpp"
#include "analysis/SummaryFieldFromMomentum.hpp"
#include "analysis/SummaryAeroUnloading.hpp"
#include "analysis/SummaryStationKeeping.hpp"
#include "analysis/SummaryTrust.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::analysis {

namespace {

struct MomentumStats {
  double start = 0.0, max = 0.0, end = 0.0;
};

/// Where the pointing is judged: the body axis put on the Sun, or seed S2's
/// orbital frame as the whole attitude's target.
struct PointingTarget {
  Eigen::Vector3d axis_B = Eigen::Vector3d::UnitX();
  bool s2_orbital = false;
};

/// What the truth says of a run: its extent, the pointing after acquisition and the wheels.
struct TruthFigures {
  std::uint64_t steps = 0;
  double sim_seconds = 0.0, pointing_max = 0.0, pointing_sum = 0.0;
  std::uint64_t pointing_count = 0;
  MomentumStats h;
  std::uint64_t late_commands = 0;
  // A wheel saturates when its momentum reaches the limit the plant holds it
  // at (sim/RigidBodyWheels.cpp); each arrival there is one event.
  std::uint64_t saturation_events = 0;
  std::array<bool, sim::kMaxWheels> saturated{};  // at the last sample, by wheel
};

/// Adds one truth sample to what the truth says of the run.
void addTruth(TruthFigures& f, const bus::Scenario& scenario, const vehicle::VehicleDescription& plant,
              const PointingTarget& target, const TruthSample& truth) {
  const double t = static_cast<double>(truth.header().sim_time_ns()) * 1e-9;
  const double momentum = bus::vec3(truth.h_wheels_body_Nms()).norm();
  if (f.steps == 0) f.h.start = momentum;
  f.h.max = std::max(f.h.max, momentum);
  f.h.end = momentum;
  f.sim_seconds = t;
  ++f.steps;
  // The slower dipole command is due every `divider` steps;
  // only a wheel command older than its step was late.
  if (truth.wheel_cmd_age_steps() > 0) ++f.late_commands;
  for (int i = 0; i < plant.body.wheel_count; ++i) {
    const double wheel_h = plant.body.wheel_inertia_kg_m2(i) * truth.wheel_speed_rad_s()[i];
    const bool at_limit = std::abs(wheel_h) >= plant.body.wheel_max_momentum_Nms(i) * (1 - 1e-9);
    if (at_limit && !f.saturated[i]) ++f.saturation_events;
    f.saturated[i] = at_limit;
  }
  if (t < scenario.acquisition_s) return;
  const Eigen::Quaterniond q_NB = bus::quat(truth.q_inertial_body());
  const Eigen::Vector3d axis_N = q_NB * target.axis_B;
  const double error =
      target.s2_orbital ? Eigen::Quaterniond(sim::R_N_S2Orbital(bus::vec3(truth.r_inertial_m()),
                                                               bus::vec3(truth.v_inertial_m_s())))
                              .angularDistance(q_NB)
                        : std::atan2(axis_N.cross(bus::vec3(truth.sun_inertial_unit())).norm(),
                                     axis_N.dot(bus::vec3(truth.sun_inertial_unit())));
  f.pointing_max = std::max(f.pointing_max, error);
  f.pointing_sum += error;
  ++f.pointing_count;
}

/// What the components' last recorded health samples counted.
struct HealthFigures {
  std::map<std::string, std::array<std::uint64_t, 3>> lateness;  // stale, overruns, deadlines missed
  nlohmann::ordered_json dropped = nlohmann::ordered_json::object();  // last count by component
  std::map<std::string, std::uint64_t> refused;                     // last count by component
  std::array<double, 3> tick_late{};  // [µs] the paced time master's last p50, p99, max
};

HealthFigures healthFigures(const bus::Recording& recording) {
  HealthFigures f;
  using HealthDef = std::remove_cvref_t<decltype(bus::topics::kHealth)>;
  recording.forEach(std::string(bus::topics::kHealth.name),
                    [&](std::uint64_t, const std::string& source, const std::vector<std::uint8_t>& bytes) {
                      const auto health = bus::deserialize<HealthDef>(bytes);
                      f.lateness[source] = {health.stale_inputs(), health.overruns(), health.deadlines_missed()};
                      f.dropped[source] = health.samples_dropped();
                      f.refused[source] = health.commands_refused();
                      if (health.tick_late_us_max() > 0) {
                        f.tick_late = {health.tick_late_us_p50(), health.tick_late_us_p99(), health.tick_late_us_max()};
                      }
                    });
  return f;
}

/// Exclusive ownership delivers one producer's samples at a time, so a change
/// of source on a topic is a hand-over (bridge <-> emulator): every switch, who
/// produced each recorded topic (emulator, bridge or external), and each
/// component's role in the scenario.
void addOwnership(nlohmann::ordered_json& s, const bus::Scenario& scenario, const bus::Recording& recording) {
  nlohmann::ordered_json switches = nlohmann::ordered_json::array();
  nlohmann::ordered_json producers = nlohmann::ordered_json::object();
  bus::forEachTopic([&](const auto& def) {
    if (def.qos != bus::QosKind::kStepped) return;
    std::string previous;
    nlohmann::ordered_json sources = nlohmann::ordered_json::array();
    std::uint64_t previous_step = 0;
    recording.forEachStamp(std::string(def.name), [&](std::uint64_t step, const std::string& source) {
      if (!previous.empty() && source != previous) {
        // gap_s: from the old owner's last sample to the new owner's first, the
        // time readers had nothing new on the topic (none when a bridge's first
        // sample carries an older step than the emulator's last).
        const double gap_steps =
            std::max(0.0, static_cast<double>(step) - static_cast<double>(previous_step));
        switches.push_back({{"time_s", static_cast<double>(step) * scenario.step_s},
                            {"topic", def.name},
                            {"from", previous},
                            {"to", source},
                            {"gap_s", gap_steps * scenario.step_s}});
      }
      if (source != previous && std::find(sources.begin(), sources.end(), source) == sources.end()) {
        sources.push_back(source);
      }
      previous = source;
      previous_step = step;
    });
    if (!sources.empty()) producers[std::string(def.name)] = sources;
  });
  s["ownership_switches"] = switches;
  s["topic_producers"] = producers;
  nlohmann::ordered_json roles = nlohmann::ordered_json::object();
  for (const auto& c : scenario.components) roles[c.name] = c.role;
  // A program is off the bus: what it did is what its bridges published.
  nlohmann::ordered_json programs = nlohmann::ordered_json::object();
  for (const auto& program : scenario.programs) {
    roles[program.name] = "program";
    nlohmann::ordered_json topics = nlohmann::ordered_json::object();
    for (const auto& [topic, sources] : producers.items()) {
      for (const auto& bridge : program.bridges) {
        if (std::find(sources.begin(), sources.end(), bridge) != sources.end()) topics[topic] = bridge;
      }
    }
    programs[program.name] = {{"command", program.command}, {"topics", topics}};
  }
  s["roles"] = roles;
  if (!scenario.programs.empty()) s["programs"] = programs;
}

}  // namespace

nlohmann::ordered_json summarize(const bus::Scenario& scenario, const std::string& recording_path,
                                 const RunOutcome& launch) {
  bus::ConfigProblems ignored;  // the scenario was checked before the run
  const vehicle::Vehicle craft = vehicle::readVehicle(scenario, ignored);
  const auto& plant = craft.truth;
  PointingTarget target;
  if (scenario.hasComponent("attitude_controller")) {
    const auto controller =
        attitude_controller::readParams(scenario, craft, {scenario.file, "attitude_controller", ""}, ignored);
    target = {controller.law.pointing_axis_B.normalized(), controller.s2_orbital.has_value()};
  }
  double capacity = plant.body.wheel_max_momentum_Nms.head(plant.body.wheel_count).minCoeff();

  const bus::Recording recording(recording_path, bus::Recording::Access::kRead);
  // The truth is read once, for every figure judged against it.
  TruthFigures truth;
  EstimatorFigures estimator(scenario);
  FieldFromMomentumFigures field_from_momentum(scenario, sim::julianDate(craft.truth.epoch), recording);
  recording.forEach(std::string(bus::topics::kTruth.name),
                    [&](std::uint64_t step, const std::string&, const std::vector<std::uint8_t>& bytes) {
                      const auto sample = bus::deserialize<std::remove_cvref_t<decltype(bus::topics::kTruth)>>(bytes);
                      addTruth(truth, scenario, plant, target, sample);
                      estimator.addTruth(step, sample);
                      field_from_momentum.addTruth(step, sample);
                    });
  std::uint64_t steps = truth.steps;
  double sim_seconds = truth.sim_seconds;

  // A decimated recording (recorder record_every_steps) holds every Nth truth
  // sample only: the run's extent is then the grants the launcher counted.
  if (!recording.meta(bus::meta::kRecordEverySteps).empty() && launch.steps > 0) {
    steps = launch.steps;
    sim_seconds = static_cast<double>(launch.steps - 1) * scenario.step_s;
  }

  nlohmann::ordered_json s;
  s["scenario"] = scenario.name;
  addCompletion(s, recording);
  s["sim_seconds"] = sim_seconds;
  s["wall_seconds"] = launch.step_seconds;
  s["launch_seconds"] = launch.launch_seconds;
  s["startup_seconds"] = launch.startup_seconds;
  s["speed_factor"] = launch.step_seconds > 0 ? sim_seconds / launch.step_seconds : 0.0;
  s["steps"] = steps;
  s["steps_per_second"] = launch.step_seconds > 0 ? static_cast<double>(steps) / launch.step_seconds : 0.0;
  s["processes"] = launch.processes;
  s["acquisition_seconds"] = scenario.acquisition_s;
  // Not measured (a run that ended before acquisition_s) is null, never a perfect 0.
  s["pointing_error_deg_max"] = truth.pointing_count ? nlohmann::ordered_json(truth.pointing_max * kRadToDeg) : nullptr;
  s["pointing_error_deg_mean"] =
      truth.pointing_count ? nlohmann::ordered_json(truth.pointing_sum / truth.pointing_count * kRadToDeg) : nullptr;
  s["wheel_capacity_Nms"] = capacity;
  s["wheel_momentum_Nms_start"] = truth.h.start;
  s["wheel_momentum_Nms_max"] = truth.h.max;
  s["wheel_momentum_Nms_end"] = truth.h.end;
  s["wheel_saturation_events"] = truth.saturation_events;
  s["wheel_momentum_fraction_max"] = capacity > 0 ? truth.h.max / capacity : 0.0;
  s["mode"] = scenario.pacing == bus::Pacing::kPaced ? "paced" : "lockstep";
  s["wheel_commands_late"] = truth.late_commands;
  if (scenario.pacing == bus::Pacing::kPaced) {
    // How evenly the ticks came: each step grant's arrival at the launcher
    // against the period grid (rig/Progress.hpp TickJitter).
    s["tick_jitter_us_p50"] = launch.tick_jitter.p50_us;
    s["tick_jitter_us_p99"] = launch.tick_jitter.p99_us;
    s["tick_jitter_us_max"] = launch.tick_jitter.max_us;
    s["ticks_missed"] = launch.tick_jitter.missed;
  }
  const HealthFigures health = healthFigures(recording);
  if (scenario.pacing == bus::Pacing::kPaced) {
    // How late the time master granted the steps, as it measured them
    // (bus/TickLateness.hpp): the tick itself, not its delivery.
    s["tick_lateness_us_p50"] = health.tick_late[0];
    s["tick_lateness_us_p99"] = health.tick_late[1];
    s["tick_lateness_us_max"] = health.tick_late[2];
  }
  addOwnership(s, scenario, recording);
  std::uint64_t stale = 0, overruns = 0, deadlines_missed = 0;
  for (const auto& [component, counts] : health.lateness) {
    stale += counts[0];
    overruns += counts[1];
    deadlines_missed += counts[2];
  }
  // [s] from the launch to each external component's first health sample.
  s["external_joined_s"] = launch.external_joined_s;
  if (!launch.restarts.empty()) s["restarts"] = launch.restarts;
  s["stale_inputs"] = stale;
  s["overruns"] = overruns;
  s["deadlines_missed"] = deadlines_missed;
  // Received samples that did not decode, as each component's last recorded
  // health counted them (a rogue or broken writer on the bus).
  std::uint64_t dropped_total = 0;
  for (const auto& [component, count] : health.dropped.items()) dropped_total += count.get<std::uint64_t>();
  s["samples_dropped"] = dropped_total;
  s["samples_dropped_by_component"] = health.dropped;
  std::uint64_t refused_total = 0;  // mode, fault and parameter commands refused with a reason
  for (const auto& [component, count] : health.refused) refused_total += count;
  s["commands_refused"] = refused_total;
  addTrustMetrics(s, recording);
  field_from_momentum.summarize(recording, s);
  summarizeMagnetic(scenario, recording, s);
  summarizeAeroUnloading(scenario, recording, s);
  summarizeStationKeeping(scenario, recording, s);
  estimator.summarize(recording, s);
  s["recording"] = recording_path;
  // The recorder's, when it stored every sample in order: reading 355 MB back
  // to hash them was two thirds of a composed day's summary.
  const std::string kept = recording.meta(bus::meta::kDigest);
  s["recording_sha256"] = kept.empty() ? recording.digest() : kept;
  summarizeThrusterSequencer(scenario, recording, s);
  return s;
}

namespace {

/// "flatsat/magnetometer: magnetometer -> magnetometer_bridge at 12.3 s (gap 0.1 s)", the
/// first three, then how many in all.
std::string ownershipSwitches(const nlohmann::ordered_json& switches) {
  constexpr std::size_t kShown = 3;
  std::ostringstream out;
  for (std::size_t i = 0; i < std::min(kShown, switches.size()); ++i) {
    const auto& w = switches[i];
    char times[64];
    std::snprintf(times, sizeof times, " at %.6g s (gap %.3g s)", w.value("time_s", 0.0), w.value("gap_s", 0.0));
    out << (i > 0 ? "; " : "") << w.value("topic", "?") << ": " << w.value("from", "?") << " -> " << w.value("to", "?")
        << times;
  }
  if (switches.size() > kShown) out << "; " << switches.size() << " in all (summary.json)";
  return out.str();
}

}  // namespace

std::string summaryTable(const nlohmann::ordered_json& summary) {
  std::ostringstream out;
  std::size_t width = 0;
  for (const auto& [key, value] : summary.items()) width = std::max(width, key.size());
  for (const auto& [key, value] : summary.items()) {
    out << "  " << key << std::string(width - key.size() + 2, ' ');
    if (value.is_number_float()) {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.6g", value.get<double>());
      out << buffer;
    } else if (value.is_string()) {
      out << value.get<std::string>();
    } else if (key == "spacecraft" && value.is_array()) {
      out << value.size() << " summaries (spacecraft-<i>/summary.json)";
    } else if (key == "ownership_switches" && value.is_array() && !value.empty()) {
      out << ownershipSwitches(value);
    } else if (value.is_array() && !value.empty() && value.front().is_object()) {
      out << value.size() << " entries (summary.json)";
    } else {
      out << value.dump();
    }
    out << '\n';
  }
  return out.str();
}

}  // namespace flatsat::analysis
