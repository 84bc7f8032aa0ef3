// SPDX-License-Identifier: Apache-2.0
#include "analysis/RunFigures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

#include "analysis/Conventions.hpp"
#include "analysis/SummaryAeroUnloading.hpp"
#include "analysis/SummaryAngleOnly.hpp"
#include "analysis/SummaryEstimator.hpp"
#include "analysis/SummaryFieldFromMomentum.hpp"
#include "analysis/SummaryMagnetic.hpp"
#include "analysis/SummaryStationKeeping.hpp"
#include "analysis/SummaryTrust.hpp"
#include "bus/Convert.hpp"
#include "bus/RecordingMeta.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "components/attitude_controller/AttitudeControllerNode.hpp"
#include "sim/Frames.hpp"
#include "sim/Time.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::analysis {

namespace {

template <const auto& Topic>
using DefOf = std::remove_cvref_t<decltype(Topic)>;

/// Where the pointing is judged: the body axis put on the Sun, or seed S2's
/// orbital frame as the whole attitude's target.
struct PointingTarget {
  Eigen::Vector3d axis_B = Eigen::Vector3d::UnitX();
  bool s2_orbital = false;
};

/// What the truth says of a run: its extent, the pointing after acquisition and the wheels.
class TruthFigures {
 public:
  TruthFigures(const bus::Scenario& scenario, const vehicle::Vehicle& craft)
      : acquisition_s_(scenario.acquisition_s), body_(craft.truth.body) {
    if (!scenario.hasComponent("attitude_controller")) return;
    bus::ConfigProblems ignored;  // the scenario was checked before the run
    const auto controller =
        attitude_controller::readParams(scenario, craft, {scenario.file, "attitude_controller", ""}, ignored);
    target_ = {controller.law.pointing_axis_B.normalized(), controller.s2_orbital.has_value()};
  }

  void add(const TruthSample& truth) {
    const double t = static_cast<double>(truth.header().sim_time_ns()) * 1e-9;
    const double momentum = bus::vec3(truth.h_wheels_body_Nms()).norm();
    if (steps_ == 0) h_start_ = momentum;
    h_max_ = std::max(h_max_, momentum);
    h_end_ = momentum;
    sim_seconds_ = t;
    ++steps_;
    // The slower dipole command is due every `divider` steps;
    // only a wheel command older than its step was late.
    if (truth.wheel_cmd_age_steps() > 0) ++late_commands_;
    // A wheel saturates when its momentum reaches the limit the plant holds it
    // at (sim/RigidBodyWheels.cpp); each arrival there is one event.
    for (int i = 0; i < body_.wheel_count; ++i) {
      const double wheel_h = body_.wheel_inertia_kg_m2(i) * truth.wheel_speed_rad_s()[i];
      const bool at_limit = std::abs(wheel_h) >= body_.wheel_max_momentum_Nms(i) * (1 - 1e-9);
      if (at_limit && !saturated_[i]) ++saturation_events_;
      saturated_[i] = at_limit;
    }
    if (t < acquisition_s_) return;
    const Eigen::Quaterniond q_NB = bus::quat(truth.q_inertial_body());
    const Eigen::Vector3d axis_N = q_NB * target_.axis_B;
    const double error =
        target_.s2_orbital ? Eigen::Quaterniond(sim::R_N_S2Orbital(bus::vec3(truth.r_inertial_m()),
                                                                  bus::vec3(truth.v_inertial_m_s())))
                                 .angularDistance(q_NB)
                           : std::atan2(axis_N.cross(bus::vec3(truth.sun_inertial_unit())).norm(),
                                        axis_N.dot(bus::vec3(truth.sun_inertial_unit())));
    pointing_max_ = std::max(pointing_max_, error);
    pointing_sum_ += error;
    ++pointing_count_;
  }

  nlohmann::ordered_json extent() const { return {{"steps", steps_}, {"sim_seconds", sim_seconds_}}; }

  nlohmann::ordered_json figures() const {
    const double capacity = body_.wheel_max_momentum_Nms.head(body_.wheel_count).minCoeff();
    nlohmann::ordered_json f;
    // Not measured (a run that ended before acquisition_s) is null, never a perfect 0.
    f["pointing_error_deg_max"] = pointing_count_ ? nlohmann::ordered_json(pointing_max_ * kRadToDeg) : nullptr;
    f["pointing_error_deg_mean"] =
        pointing_count_ ? nlohmann::ordered_json(pointing_sum_ / pointing_count_ * kRadToDeg) : nullptr;
    f["wheel_capacity_Nms"] = capacity;
    f["wheel_momentum_Nms_start"] = h_start_;
    f["wheel_momentum_Nms_max"] = h_max_;
    f["wheel_momentum_Nms_end"] = h_end_;
    f["wheel_saturation_events"] = saturation_events_;
    f["wheel_momentum_fraction_max"] = capacity > 0 ? h_max_ / capacity : 0.0;
    f["wheel_commands_late"] = late_commands_;
    return f;
  }

 private:
  double acquisition_s_;
  sim::RigidBodyParams body_;
  PointingTarget target_;
  std::uint64_t steps_ = 0, pointing_count_ = 0, late_commands_ = 0, saturation_events_ = 0;
  double sim_seconds_ = 0.0, pointing_max_ = 0.0, pointing_sum_ = 0.0;
  double h_start_ = 0.0, h_max_ = 0.0, h_end_ = 0.0;
  std::array<bool, sim::kMaxWheels> saturated_{};  // at the last sample, by wheel
};

/// Exclusive ownership delivers one producer's samples at a time, so a change
/// of source on a topic is a hand-over (bridge <-> emulator): every switch, and
/// who produced each recorded topic (emulator, bridge or external), from the
/// stamps in the order the recorder received them.
class OwnershipFigures {
 public:
  explicit OwnershipFigures(double step_s) : step_s_(step_s) {
    bus::forEachTopic([&](const auto& def) {
      if (def.qos == bus::QosKind::kStepped) topics_.emplace_back(std::string(def.name), Owners{});
    });
  }

  /// A sample of a topic that is not stepped counts for nothing.
  void add(std::string_view topic, std::uint64_t step, std::string_view source) {
    const auto it = std::find_if(topics_.begin(), topics_.end(), [&](const auto& t) { return t.first == topic; });
    if (it == topics_.end()) return;
    Owners& o = it->second;
    if (!o.previous.empty() && source != o.previous) {
      // gap_s: from the old owner's last sample to the new owner's first, the
      // time readers had nothing new on the topic (none when a bridge's first
      // sample carries an older step than the emulator's last).
      const double gap_steps = std::max(0.0, static_cast<double>(step) - static_cast<double>(o.previous_step));
      o.switches.push_back({{"time_s", static_cast<double>(step) * step_s_},
                            {"topic", it->first},
                            {"from", o.previous},
                            {"to", std::string(source)},
                            {"gap_s", gap_steps * step_s_}});
    }
    if (source != o.previous && std::find(o.sources.begin(), o.sources.end(), source) == o.sources.end()) {
      o.sources.emplace_back(source);
    }
    o.previous = source;
    o.previous_step = step;
  }

  nlohmann::ordered_json figures() const {
    nlohmann::ordered_json switches = nlohmann::ordered_json::array();
    nlohmann::ordered_json producers = nlohmann::ordered_json::object();
    for (const auto& [topic, o] : topics_) {
      for (const auto& s : o.switches) switches.push_back(s);
      if (!o.sources.empty()) producers[topic] = o.sources;
    }
    return {{"ownership_switches", switches}, {"topic_producers", producers}};
  }

 private:
  struct Owners {
    std::string previous;
    std::uint64_t previous_step = 0;
    std::vector<std::string> sources;
    std::vector<nlohmann::ordered_json> switches;
  };
  double step_s_;
  std::vector<std::pair<std::string, Owners>> topics_;  // in the topics' order
};

}  // namespace

struct RunFigures::Parts {
  Parts(const bus::Scenario& scenario, const vehicle::Vehicle& craft)
      : truth(scenario, craft),
        ownership(scenario.step_s),
        estimator(scenario.acquisition_s),
        field_from_momentum(scenario.acquisition_s, sim::julianDate(craft.truth.epoch)),
        magnetic(scenario, craft),
        aero(scenario, craft),
        station_keeping(scenario, craft),
        thruster(scenario, craft) {}
  TruthFigures truth;
  OwnershipFigures ownership;
  BusFigures bus;
  EstimatorFigures estimator;
  FieldFromMomentumFigures field_from_momentum;
  MagneticFigures magnetic;
  AeroUnloadingFigures aero;
  StationKeepingFigures station_keeping;
  ThrusterSequencerFigures thruster;
};

RunFigures::RunFigures(const bus::Scenario& scenario) {
  bus::ConfigProblems ignored;  // the scenario was checked before the run
  parts_ = std::make_unique<Parts>(scenario, vehicle::readVehicle(scenario, ignored));
}

RunFigures::~RunFigures() = default;

void RunFigures::add(const bus::StoredSample& s) {
  Parts& p = *parts_;
  const auto decode = [&s]<const auto& Topic>() { return bus::deserialize<DefOf<Topic>>(s.payload, s.size); };
  p.ownership.add(s.topic, s.step, s.source);
  if (s.topic == bus::topics::kTruth.name) {
    const auto truth = decode.template operator()<bus::topics::kTruth>();
    p.truth.add(truth);
    p.estimator.addTruth(s.step, truth);
    p.field_from_momentum.addTruth(s.step, truth);
    p.magnetic.addTruth(truth);
    p.aero.addTruth(s.step, truth);
    p.station_keeping.addTruth(truth);
    p.thruster.addTruth(s.step, truth);
  } else if (s.topic == bus::topics::kAttitudeEstimate.name) {
    p.estimator.addEstimate(s.step, decode.template operator()<bus::topics::kAttitudeEstimate>());
  } else if (s.topic == bus::topics::kFieldEstimate.name) {
    p.field_from_momentum.addField(s.step, decode.template operator()<bus::topics::kFieldEstimate>());
  } else if (s.topic == bus::topics::kFlapCmd.name) {
    p.aero.addFlapCmd(s.step, decode.template operator()<bus::topics::kFlapCmd>());
  } else if (s.topic == bus::topics::kThrusterCmd.name) {
    p.thruster.addCmd(s.step, decode.template operator()<bus::topics::kThrusterCmd>());
  } else if (s.topic == bus::topics::kStepGrant.name) {
    p.bus.addGrant(s.step, decode.template operator()<bus::topics::kStepGrant>());
  } else if (s.topic == bus::topics::kHealth.name) {
    p.bus.addHealth(s.step, std::string(s.source), decode.template operator()<bus::topics::kHealth>());
  } else if (s.topic == bus::topics::kFaultEvent.name) {
    p.bus.addFaultEvent(s.step, std::string(s.source), decode.template operator()<bus::topics::kFaultEvent>());
  }
}

nlohmann::ordered_json RunFigures::figures() const {
  const Parts& p = *parts_;
  nlohmann::ordered_json f;
  f["extent"] = p.truth.extent();
  f["grants"] = p.bus.grants();
  f["truth"] = p.truth.figures();
  nlohmann::ordered_json timing = nlohmann::ordered_json::object();
  p.bus.tickLateness(timing);
  f["timing"] = timing;
  f["ownership"] = p.ownership.figures();
  const auto group = [&f](const char* name, const auto& fill) {
    nlohmann::ordered_json g = nlohmann::ordered_json::object();
    fill(g);
    f[name] = g;
  };
  group("lateness", [&](auto& g) { p.bus.lateness(g); });
  group("trust", [&](auto& g) { p.bus.trust(g); });
  group("s0", [&](auto& g) { p.field_from_momentum.summarize(g); });
  group("magnetic", [&](auto& g) { p.magnetic.summarize(g); });
  group("aero", [&](auto& g) { p.aero.summarize(g); });
  group("station_keeping", [&](auto& g) { p.station_keeping.summarize(g); });
  group("estimator", [&](auto& g) { p.estimator.summarize(g); });
  group("thruster", [&](auto& g) { p.thruster.summarize(g); });
  return f;
}

nlohmann::ordered_json recordedFigures(const bus::Scenario& scenario, const bus::Recording& recording) {
  if (const std::string kept = recording.meta(bus::meta::kFigures); !kept.empty()) {
    try {
      return nlohmann::ordered_json::parse(kept);
    } catch (const nlohmann::json::exception&) {  // not as its recorder wrote it: computed again
    }
  }
  RunFigures figures(scenario);
  recording.forEachStored([&figures](const bus::StoredSample& sample) { figures.add(sample); });
  return figures.figures();
}

void recordRunFigures() {
  recorder::setSampleFiguresFactory(
      [](const bus::Scenario& scenario) { return std::make_unique<RunFigures>(scenario); });
}

}  // namespace flatsat::analysis
