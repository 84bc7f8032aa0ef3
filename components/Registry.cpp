// SPDX-License-Identifier: Apache-2.0
#include "components/Registry.hpp"

#include "components/attitude_controller/AttitudeControllerNode.hpp"
#include "components/estimator/EstimatorNode.hpp"
#include "components/gyro/GyroNode.hpp"
#include "components/magnetometer/MagnetometerNode.hpp"
#include "components/magnetometer_bridge/MagnetometerBridgeNode.hpp"
#include "components/magnetometer_device/MagnetometerDeviceNode.hpp"
#include "components/recorder/RecorderNode.hpp"
#include "components/star_tracker/StarTrackerNode.hpp"
#include "components/station_keeping/StationKeepingNode.hpp"
#include "components/sun_sensor/SunSensorNode.hpp"
#include "components/thruster_sequencer/ThrusterSequencerNode.hpp"
#include "components/unloading_controller/UnloadingControllerNode.hpp"
#include "components/wheel_tach/WheelTachNode.hpp"
#include "sim/DynamicsServerNode.hpp"
#include "sim/DynamicsServerParams.hpp"

namespace flatsat {

namespace {

/// A kind whose node composes: `NodeType(bus, options, read(...))`.
template <class NodeType, class Read>
ComponentKind kind(const std::string& name, Read read) {
  return {name, "flatsat-" + name,
          [read](const bus::Scenario& s, const bus::NodeArgs& a, bus::ConfigProblems& p) {
            read(s, a, p);
          },
          [read](bus::Bus& bus, bus::NodeOptions options, const bus::Scenario& s,
                 const bus::NodeArgs& a) -> std::unique_ptr<bus::Node> {
            bus::ConfigProblems problems;
            auto params = read(s, a, problems);
            if (!problems.empty()) throw bus::ScenarioError(a.name + ":\n" + problems.joined());
            return std::make_unique<NodeType>(bus, std::move(options), params);
          },
          ""};
}

/// A kind that only runs as its own process, for `reason`; its node reads `reads`.
template <class Read>
ComponentKind processOnly(const std::string& name, Read read, const std::string& reason,
                          std::vector<std::string> reads) {
  return {name, "flatsat-" + name,
          [read](const bus::Scenario& s, const bus::NodeArgs& a, bus::ConfigProblems& p) {
            read(s, a, p);
          },
          {}, reason, std::move(reads)};
}

}  // namespace

const std::vector<ComponentKind>& componentKinds() {
  static const std::vector<ComponentKind> kinds = {
      kind<sim::DynamicsServerNode>(
          "dynamics_server",
          [](const bus::Scenario& s, const bus::NodeArgs& a, bus::ConfigProblems& p) {
            return sim::readDynamicsServerParams(s, a.name, p);
          }),
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
      processOnly("magnetometer_bridge", magnetometer_bridge::readParams,
                  "a hardware bridge: it publishes as its serial device delivers, on the wall "
                  "clock, over the emulator at a higher DDS ownership strength",
                  {std::string(bus::topics::kStepGrant.name)}),  // MagnetometerBridgeNode::grants_
      processOnly("magnetometer_device", magnetometer_device::readParams,
                  "a device stand-in: it plays a real unit on a pseudo-terminal, on the wall clock",
                  {std::string(bus::topics::kTruth.name)}),  // MagnetometerDeviceNode::truth_
      kind<thruster_sequencer::ThrusterSequencerNode>("thruster_sequencer",
                                                      thruster_sequencer::readParams),
      kind<star_tracker::StarTrackerNode>("star_tracker", star_tracker::readParams),
      kind<station_keeping::StationKeepingNode>("station_keeping", station_keeping::readParams),
  };
  return kinds;
}

const ComponentKind* findComponentKind(const std::string& name) {
  for (const auto& k : componentKinds()) {
    if (k.name == name) return &k;
  }
  return nullptr;
}

std::vector<std::string> checkScenario(const bus::Scenario& scenario, const std::string& out_dir) {
  bus::ConfigProblems problems;
  for (const auto& component : scenario.components) {
    const ComponentKind* k = findComponentKind(component.name);
    if (k == nullptr) {
      std::string known;
      for (const auto& each : componentKinds()) known += " " + each.name;
      problems.add(scenario.file + ": components." + component.name +
                   ": unknown component (known:" + known + ")");
      continue;
    }
    k->check(scenario, {scenario.file, component.name, out_dir}, problems);
  }
  for (const char* required : {"dynamics_server", "recorder"}) {
    if (!scenario.hasComponent(required)) {
      problems.add(scenario.file + ": components: the rig needs a " + std::string(required));
    }
  }
  return problems.list();
}

}  // namespace flatsat
