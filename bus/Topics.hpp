// SPDX-License-Identifier: Apache-2.0
#pragma once
// The topic registry: the one place that binds a topic name to its IDL type,
// its QoS preset and its logical producer (PX4's ORB_ID()). Nothing else
// writes topic-name literals.
#include <string_view>

#include "bus/Qos.hpp"
#include "msg/ActuationPubSubTypes.h"
#include "msg/CoilsPubSubTypes.h"
#include "msg/CommandsPubSubTypes.h"
#include "msg/EstimationPubSubTypes.h"
#include "msg/FaultsPubSubTypes.h"
#include "msg/HealthPubSubTypes.h"
#include "msg/ModesPubSubTypes.h"
#include "msg/SensorsPubSubTypes.h"
#include "msg/StationKeepingPubSubTypes.h"
#include "msg/StepPubSubTypes.h"
#include "msg/TruthPubSubTypes.h"

namespace flatsat::bus {

template <class Sample, class PubSub>
struct TopicDef {
  using Type = Sample;
  using PubSubType = PubSub;
  std::string_view name;
  QosKind qos;
  /// Component that publishes it; empty: every component does.
  std::string_view producer;
};

namespace topics {
using namespace flatsat::msg;
inline constexpr TopicDef<StepGrant, StepGrantPubSubType> kStepGrant{
    "flatsat/step_grant", QosKind::kProtocol, "dynamics_server"};
inline constexpr TopicDef<StepDone, StepDonePubSubType> kStepDone{
    "flatsat/step_done", QosKind::kProtocol, ""};
inline constexpr TopicDef<TruthState, TruthStatePubSubType> kTruth{
    "flatsat/truth", QosKind::kStepped, "dynamics_server"};
inline constexpr TopicDef<MagnetometerReading, MagnetometerReadingPubSubType> kMagnetometer{
    "flatsat/magnetometer", QosKind::kStepped, "magnetometer"};
inline constexpr TopicDef<SunSensorReading, SunSensorReadingPubSubType> kSunSensor{
    "flatsat/sun_sensor", QosKind::kStepped, "sun_sensor"};
inline constexpr TopicDef<GyroReading, GyroReadingPubSubType> kGyro{
    "flatsat/gyro", QosKind::kStepped, "gyro"};
inline constexpr TopicDef<StarTrackerReading, StarTrackerReadingPubSubType> kStarTracker{
    "flatsat/star_tracker", QosKind::kStepped, "star_tracker"};
inline constexpr TopicDef<WheelTachReading, WheelTachReadingPubSubType> kWheelTach{
    "flatsat/wheel_tach", QosKind::kStepped, "wheel_tach"};
inline constexpr TopicDef<AttitudeEstimate, AttitudeEstimatePubSubType> kAttitudeEstimate{
    "flatsat/attitude_estimate", QosKind::kStepped, "estimator"};
inline constexpr TopicDef<FieldEstimate, FieldEstimatePubSubType> kFieldEstimate{
    "flatsat/field_estimate", QosKind::kStepped, "estimator"};
inline constexpr TopicDef<CoilRequest, CoilRequestPubSubType> kCoilRequest{
    "flatsat/coil_request", QosKind::kStepped, "estimator"};
inline constexpr TopicDef<CoilWindow, CoilWindowPubSubType> kCoilWindow{
    "flatsat/coil_window", QosKind::kStepped, "unloading_controller"};
inline constexpr TopicDef<WheelTorqueCmd, WheelTorqueCmdPubSubType> kWheelTorqueCmd{
    "flatsat/wheel_torque_cmd", QosKind::kStepped, "attitude_controller"};
inline constexpr TopicDef<DipoleCmd, DipoleCmdPubSubType> kDipoleCmd{
    "flatsat/dipole_cmd", QosKind::kStepped, "unloading_controller"};
inline constexpr TopicDef<FlapCmd, FlapCmdPubSubType> kFlapCmd{
    "flatsat/flap_cmd", QosKind::kStepped, "unloading_controller"};
inline constexpr TopicDef<ThrusterCmd, ThrusterCmdPubSubType> kThrusterCmd{
    "flatsat/thruster_cmd", QosKind::kStepped, "thruster_sequencer"};
inline constexpr TopicDef<StationKeepingPlan, StationKeepingPlanPubSubType> kStationKeepingPlan{
    "flatsat/station_keeping_plan", QosKind::kStepped, "station_keeping"};
inline constexpr TopicDef<Health, HealthPubSubType> kHealth{
    "flatsat/health", QosKind::kState, ""};
inline constexpr TopicDef<FaultCmd, FaultCmdPubSubType> kFaultCmd{
    "flatsat/fault_cmd", QosKind::kCommand, ""};
inline constexpr TopicDef<FaultEvent, FaultEventPubSubType> kFaultEvent{
    "flatsat/fault_event", QosKind::kCommand, ""};
/// Not published: the recorder's rows of what readers held under a bus fault.
inline constexpr TopicDef<BusDelivery, BusDeliveryPubSubType> kBusDelivery{
    "flatsat/bus_delivery", QosKind::kCommand, "recorder"};
inline constexpr TopicDef<ModeCmd, ModeCmdPubSubType> kUnloadingModeCmd{
    "flatsat/unloading_mode_cmd", QosKind::kCommand, ""};
inline constexpr TopicDef<ParamCmd, ParamCmdPubSubType> kParamCmd{
    "flatsat/param_cmd", QosKind::kCommand, ""};
inline constexpr TopicDef<CommandAck, CommandAckPubSubType> kCommandAck{
    "flatsat/command_ack", QosKind::kCommand, ""};
/// Not recorded: the settable parameters' values now (param_cmd and command_ack record every change).
inline constexpr TopicDef<ParamState, ParamStatePubSubType> kParamState{
    "flatsat/param_state", QosKind::kState, ""};
}  // namespace topics

/// Calls f(def) for every topic of the registry (recorder, tools).
template <class F>
void forEachTopic(F&& f) {
  using namespace topics;
  f(kStepGrant); f(kStepDone); f(kTruth); f(kMagnetometer); f(kSunSensor); f(kGyro);
  f(kWheelTach); f(kAttitudeEstimate); f(kWheelTorqueCmd); f(kDipoleCmd); f(kHealth);
  f(kFaultCmd); f(kFaultEvent); f(kFieldEstimate); f(kCoilRequest); f(kCoilWindow);
  f(kThrusterCmd);
  f(kUnloadingModeCmd); f(kParamCmd); f(kCommandAck);
  f(kStarTracker); f(kFlapCmd); f(kBusDelivery); f(kStationKeepingPlan); f(kParamState);
}

/// Whether `name` is a stepped topic of the registry (a bus fault's target).
inline bool isSteppedTopic(std::string_view name) {
  bool found = false;
  forEachTopic([&](const auto& def) { found = found || (def.name == name && def.qos == QosKind::kStepped); });
  return found;
}

}  // namespace flatsat::bus
