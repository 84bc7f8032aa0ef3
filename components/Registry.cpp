// SPDX-License-Identifier: Apache-2.0
#include "components/Registry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

#include <spdlog/fmt/fmt.h>

#include "bus/NearestName.hpp"
#include "components/attitude_controller/AttitudeControllerNode.hpp"
#include "components/dynamics_server/DynamicsServerNode.hpp"
#include "components/estimator/EstimatorNode.hpp"
#include "components/gyro/GyroNode.hpp"
#include "components/magnetometer/MagnetometerNode.hpp"
#include "components/device_bridge/BridgeableTopics.hpp"
#include "components/device_bridge/DeviceBridgeNode.hpp"
#include "components/device_sim/DeviceSimNode.hpp"
#include "components/recorder/RecorderNode.hpp"
#include "components/star_tracker/StarTrackerNode.hpp"
#include "components/station_keeping/StationKeepingNode.hpp"
#include "components/sun_sensor/SunSensorNode.hpp"
#include "components/thruster_sequencer/ThrusterSequencerNode.hpp"
#include "components/unloading_controller/UnloadingControllerNode.hpp"
#include "components/wheel_tach/WheelTachNode.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat {

namespace {

/// A reader `read(scenario, vehicle, args, problems)`, or one of a component
/// that needs nothing of the vehicle, `read(scenario, args, problems)`.
template <class Read>
auto readWith(const Read& read, const bus::Scenario& s, const vehicle::Vehicle& v, const bus::NodeArgs& a,
              bus::ConfigProblems& p) {
  if constexpr (std::is_invocable_v<Read, const bus::Scenario&, const vehicle::Vehicle&, const bus::NodeArgs&,
                                    bus::ConfigProblems&>) {
    return read(s, v, a, p);
  } else {
    return read(s, a, p);
  }
}

/// A kind whose node composes: `NodeType(bus, options, read(...))`.
template <class NodeType, class Read>
ComponentKind kind(const std::string& name, Read read) {
  return {name, "flatsat-" + name,
          [read](const bus::Scenario& s, const vehicle::Vehicle& v, const bus::NodeArgs& a, bus::ConfigProblems& p) {
            readWith(read, s, v, a, p);
          },
          [read](bus::Bus& bus, bus::NodeOptions options, const bus::Scenario& s, const vehicle::Vehicle& v,
                 const bus::NodeArgs& a) -> std::unique_ptr<bus::Node> {
            bus::ConfigProblems problems;
            auto params = readWith(read, s, v, a, problems);
            if (!problems.empty()) throw bus::ScenarioError(a.name + ":\n" + problems.joined());
            return std::make_unique<NodeType>(bus, std::move(options), params);
          },
          ""};
}

/// A kind that only runs as its own process, for `reason`; its node reads `reads`.
template <class Read>
ComponentKind processOnly(const std::string& name, const std::string& executable, Read read, const std::string& reason,
                          std::vector<std::string> reads) {
  // Every bus::Node takes bus-fault commands (Node::bus_fault_commands_): without the
  // grant, a secured rig refuses its reader and the process fails at its start.
  reads.emplace_back(bus::topics::kFaultCmd.name);
  return {name, executable,
          [read](const bus::Scenario& s, const vehicle::Vehicle& v, const bus::NodeArgs& a, bus::ConfigProblems& p) {
            readWith(read, s, v, a, p);
          },
          {}, reason, std::move(reads)};
}

/// A reaction wheel unit's bridge (a wheel_tach_bridge whose description takes commands)
/// and the plant's wheels_follow go together: without it the unit's torques never reach
/// the body; with it and no unit, the plant would follow a tachometer.
void checkWheelUnit(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle, bus::ConfigProblems& problems) {
  const std::string bridge = std::string(bus::topics::kWheelTach.producer) + "_bridge";
  if (!scenario.hasComponent(bridge) || !scenario.hasComponent("dynamics_server")) return;
  bus::ConfigProblems reported_by_each;
  const auto unit = device_bridge::readParams(scenario, vehicle, {scenario.file, bridge, ""}, reported_by_each);
  const auto server = dynamics_server::readParams(scenario, vehicle, {scenario.file, "dynamics_server", ""},
                                                  reported_by_each);
  if (!reported_by_each.list().empty()) return;
  const bool actuator = unit.command_mapping.has_value();
  const auto where = scenario.file + ": components.";
  const auto schedule = scenario.schedule();
  const auto tach = schedule.find(std::string(bus::topics::kWheelTach.producer));
  if (actuator && tach != schedule.end() && tach->second != 1) {
    // The unit answers every command; on a slower tachometer topic the answers stamped
    // between its due steps are no one's, and the plant would follow every other one.
    problems.add(where + std::string(bus::topics::kWheelTach.producer) +
                 ".rate_divider: a reaction wheel unit answers every step: give it 1 (it is " +
                 std::to_string(tach->second) + ")");
  }
  if (actuator && server.wheels_follow != bridge) {
    problems.add(where + "dynamics_server: " + bridge + " commands a reaction wheel unit: set wheels_follow: " + bridge +
                 " so that the plant's wheels turn as the unit's do");
  } else if (!actuator && server.wheels_follow == bridge) {
    problems.add(where + "dynamics_server: wheels_follow: " + bridge + " reads a tachometer (" + unit.protocol.file +
                 " has no command frame): the plant would follow speeds nobody drives");
  }
}

/// What components need of each other's settings, checked where the whole rig is seen.
void checkRig(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle, bus::ConfigProblems& problems) {
  checkWheelUnit(scenario, vehicle, problems);
  if (!scenario.hasComponent("station_keeping")) return;
  const auto where = scenario.file + ": components.station_keeping: ";
  if (vehicle.truth.orbit_track.propagator != sim::OrbitPropagation::kNumerical) {
    problems.add(where + "needs orbit.propagator: numerical (the thrust must move the orbit)");
  }
  bus::ConfigProblems reported_by_the_server;
  const auto server = dynamics_server::readParams(scenario, vehicle, {scenario.file, "dynamics_server", ""},
                                                  reported_by_the_server);
  if (!server.dynamics.attitude_held) {
    problems.add(where + "needs components.dynamics_server.attitude: held_east_north_zenith (the thrusters' frame)");
  }
}

}  // namespace

const std::vector<ComponentKind>& componentKinds() {
  static const std::vector<ComponentKind> kinds = {
      kind<dynamics_server::DynamicsServerNode>("dynamics_server", dynamics_server::readParams),
      kind<magnetometer::MagnetometerNode>("magnetometer", magnetometer::readParams),
      kind<sun_sensor::SunSensorNode>("sun_sensor", sun_sensor::readParams),
      kind<gyro::GyroNode>("gyro", gyro::readParams),
      kind<wheel_tach::WheelTachNode>("wheel_tach", wheel_tach::readParams),
      kind<estimator::EstimatorNode>("estimator", estimator::readParams),
      kind<attitude_controller::AttitudeControllerNode>("attitude_controller",
                                                        attitude_controller::readParams),
      kind<unloading_controller::UnloadingControllerNode>("unloading_controller",
                                                          unloading_controller::readParams),
      kind<recorder::RecorderNode>("recorder", recorder::readParams),
      kind<thruster_sequencer::ThrusterSequencerNode>("thruster_sequencer",
                                                      thruster_sequencer::readParams),
      kind<star_tracker::StarTrackerNode>("star_tracker", star_tracker::readParams),
      kind<station_keeping::StationKeepingNode>("station_keeping", station_keeping::readParams),
  };
  static const std::vector<ComponentKind> with_devices = [] {
    auto all = kinds;
    // A hardware bridge for every box that publishes a stepped topic (the truth is the
    // simulation's own), and a device stand-in for every sensor the truth can drive.
    std::vector<std::string> producers;
    bus::forEachTopic([&](const auto& def) {
      const std::string producer(def.producer);
      if (def.qos != bus::QosKind::kStepped || producer.empty() || producer == "dynamics_server") return;
      if (std::find(producers.begin(), producers.end(), producer) == producers.end()) producers.push_back(producer);
    });
    for (const auto& producer : producers) {
      // DeviceBridgeNode's readers: the grants, and an actuator's command topic.
      std::vector<std::string> reads = {std::string(bus::topics::kStepGrant.name)};
      if (const auto command = device_bridge::actuatorCommandTopic(producer); !command.empty()) reads.push_back(command);
      all.push_back(processOnly(producer + "_bridge", "flatsat-device_bridge", device_bridge::readParams,
                                "a hardware bridge: it publishes as its serial device delivers, on the wall "
                                "clock, over the emulator at a higher DDS ownership strength",
                                std::move(reads)));
    }
    for (const auto* sensor : {&bus::topics::kMagnetometer.name, &bus::topics::kSunSensor.name, &bus::topics::kGyro.name,
                               &bus::topics::kWheelTach.name, &bus::topics::kStarTracker.name}) {
      all.push_back(processOnly(device_bridge::bridgeableProducer(*sensor) + "_device", "flatsat-device_sim",
                                device_sim::readParams,
                                "a device stand-in: it plays a real unit on a pseudo-terminal, on the wall clock",
                                // DeviceSimNode's readers: the truth, or (source: bus) its sensor's topic
                                {std::string(bus::topics::kTruth.name), std::string(*sensor)}));
    }
    return all;
  }();
  return with_devices;
}

const ComponentKind* findComponentKind(const std::string& name) {
  for (const auto& k : componentKinds()) {
    if (k.name == name) return &k;
  }
  return nullptr;
}

std::optional<thruster_sequencer::BrakingReach> angleOnlyBrakingReach(const bus::Scenario& scenario,
                                                                      const vehicle::Vehicle& vehicle) {
  if (!scenario.hasComponent("thruster_sequencer") || !scenario.hasComponent("dynamics_server")) return std::nullopt;
  bus::ConfigProblems problems;
  const auto sequencer =
      thruster_sequencer::readParams(scenario, vehicle, {scenario.file, "thruster_sequencer", ""}, problems);
  const auto server = dynamics_server::readParams(scenario, vehicle, {scenario.file, "dynamics_server", ""}, problems);
  if (!problems.empty() || sequencer.mode != thruster_sequencer::ThrusterSequencerParams::Mode::kAngleOnly) {
    return std::nullopt;
  }
  const auto& params = sequencer.angle_only;
  const thruster_sequencer::AngleOnlySequencer law(params);
  thruster_sequencer::BrakingDrift drift;
  drift.pulse_delta_rate_rad_s = std::min(std::abs(law.pulseDeltaRate_rad_s(1)), std::abs(law.pulseDeltaRate_rad_s(-1)));
  drift.drift_rate_rad_s = params.axis_B.dot(server.dynamics.w0_NB_B_rad_s);
  drift.sample_period_s = std::max(scenario.componentStep_s("sun_sensor"), params.step_s);
  drift.pulse_on_time_s = params.pulse_on_time_s;
  // Pulses fall on command steps: a T2 between two steps acts as the later one.
  auto cycle = params.cycle;
  cycle.braking_interval_s = std::ceil(cycle.braking_interval_s / params.step_s - 1e-9) * params.step_s;
  return thruster_sequencer::brakingReach(cycle, drift);
}

std::vector<std::string> scenarioCautions(const bus::Scenario& scenario) {
  bus::ConfigProblems problems;
  const vehicle::Vehicle vehicle = vehicle::readVehicle(scenario, problems);
  std::vector<std::string> cautions;
  if (!problems.empty()) return cautions;
  if (const auto reach = angleOnlyBrakingReach(scenario, vehicle); reach && !reach->holds) {
    constexpr double kDeg = 180.0 / std::numbers::pi;
    // Pulses fall on command steps: the longest T2 that holds, rounded down to one.
    const double step_s = scenario.componentStep_s("thruster_sequencer");
    const double on_steps_s = std::floor(reach->longest_interval_s / step_s + 1e-9) * step_s;
    cautions.push_back(fmt::format(
        "{}: components.thruster_sequencer.braking_interval_s: seed S1's condition on T2 does not hold: "
        "braking {} pulses from {:.4g} deg/s takes the angle {:.4g} deg past the target, beyond the nearer "
        "limit {:.4g} deg away; braking_interval_s <= {:.4g} s would hold it ({})",
        scenario.file, reach->braking_pulses, reach->drift_rate_rad_s * kDeg, reach->travel_rad * kDeg,
        reach->room_rad * kDeg, reach->longest_interval_s,
        on_steps_s > 0.0 ? fmt::format("on {:.4g} s command steps: {:.4g} s", step_s, on_steps_s)
                         : fmt::format("none on {:.4g} s command steps: a shorter step is needed", step_s)));
  }
  return cautions;
}

std::vector<std::string> checkScenario(const bus::Scenario& scenario, const std::string& out_dir) {
  bus::ConfigProblems problems;
  const vehicle::Vehicle vehicle = vehicle::readVehicle(scenario, problems);
  for (const auto& component : scenario.components) {
    const ComponentKind* k = findComponentKind(component.name);
    if (k == nullptr) {
      std::string known;
      std::vector<std::string> names;
      for (const auto& each : componentKinds()) {
        known += " " + each.name;
        names.push_back(each.name);
      }
      problems.add(scenario.file + ": components." + component.name + ": unknown component" +
                   bus::didYouMean(component.name, names) + " (known:" + known + ")");
      continue;
    }
    k->check(scenario, vehicle, {scenario.file, component.name, out_dir}, problems);
  }
  for (const char* required : {"dynamics_server", "recorder"}) {
    if (!scenario.hasComponent(required)) {
      problems.add(scenario.file + ": components: the rig needs a " + std::string(required));
    }
  }
  checkRig(scenario, vehicle, problems);
  return problems.list();
}

}  // namespace flatsat
