// SPDX-License-Identifier: Apache-2.0
#include "bus/SampleChecks.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bus/Topics.hpp"
#include "msg/MsgJson.hpp"

namespace flatsat::bus {
namespace {

template <std::size_t N>
bool within(const std::array<double, N>& v, double bound) {
  return std::all_of(v.begin(), v.end(), [bound](double x) { return std::abs(x) <= bound; });
}

template <std::size_t N>
bool nonNegativeWithin(const std::array<double, N>& v, double bound) {
  return std::all_of(v.begin(), v.end(), [bound](double x) { return x >= 0.0 && x <= bound; });
}

template <std::size_t N>
bool unitNorm(const std::array<double, N>& v) {
  double norm2 = 0.0;
  for (double x : v) norm2 += x * x;
  return std::abs(std::sqrt(norm2) - 1.0) <= kUnitNormTolerance;
}

// The ranges of each topic beyond finiteness (firstNonFinite, generated from the IDL).
Breach rangeOf(const msg::TruthState& s) {
  if (!unitNorm(s.q_inertial_body())) return {"q_inertial_body", "not a unit quaternion"};
  if (s.wheel_count() > s.wheel_speed_rad_s().size()) return {"wheel_count", "more wheels than the type holds"};
  return {};
}
Breach rangeOf(const msg::MagnetometerReading& s) {
  if (!within(s.b_body_T(), kMaxFieldT)) return {"b_body_T", "beyond 1e-3 T on an axis"};
  return {};
}
Breach rangeOf(const msg::SunSensorReading& s) {
  if (s.valid() && !unitNorm(s.sun_body_unit())) return {"sun_body_unit", "valid but not a unit vector"};
  if (!within(s.sun_body_unit(), 1.0 + kUnitNormTolerance)) return {"sun_body_unit", "beyond 1 on an axis"};
  if (s.cell_count() > s.cell_output().size()) return {"cell_count", "more cells than the type holds"};
  if (!within(s.cell_output(), kMaxCellOutput)) return {"cell_output", "beyond 10 suns"};
  return {};
}
Breach rangeOf(const msg::GyroReading& s) {
  if (!within(s.w_body_rad_s(), kMaxBodyRateRadS)) return {"w_body_rad_s", "beyond 50 rad/s on an axis"};
  return {};
}
Breach rangeOf(const msg::StarTrackerReading& s) {
  if (s.valid() && !unitNorm(s.q_inertial_body())) return {"q_inertial_body", "valid but not a unit quaternion"};
  if (!within(s.q_inertial_body(), 1.0 + kUnitNormTolerance)) return {"q_inertial_body", "beyond 1 in a component"};
  return {};
}
Breach rangeOf(const msg::WheelTachReading& s) {
  if (!within(s.wheel_speed_rad_s(), kMaxWheelSpeedRadS)) return {"wheel_speed_rad_s", "beyond 2000 rad/s"};
  return {};
}
Breach rangeOf(const msg::AttitudeEstimate& s) {
  if (s.valid() && !unitNorm(s.q_inertial_body())) return {"q_inertial_body", "valid but not a unit quaternion"};
  if (!within(s.w_body_rad_s(), kMaxBodyRateRadS)) return {"w_body_rad_s", "beyond 50 rad/s on an axis"};
  if (!within(s.gyro_bias_body_rad_s(), kMaxBodyRateRadS)) return {"gyro_bias_body_rad_s", "beyond 50 rad/s"};
  return {};
}
Breach rangeOf(const msg::FieldEstimate& s) {
  if (!within(s.b_body_T(), kMaxFieldT) || !within(s.b_cycle_body_T(), kMaxFieldT)) {
    return {"b_body_T", "beyond 1e-3 T on an axis"};
  }
  return {};
}
Breach rangeOf(const msg::CoilRequest& s) {
  if (!within(s.m_body_Am2(), kMaxDipoleAm2)) return {"m_body_Am2", "beyond 1e4 A m^2"};
  const std::array<double, 3> phases{s.quiet_s(), s.pulse_s(), s.quiet_after_s()};
  if (!nonNegativeWithin(phases, kMaxDurationS)) return {"pulse_s", "a phase is negative or beyond 1e5 s"};
  return {};
}
Breach rangeOf(const msg::CoilWindow& s) {
  if (!within(s.m_body_Am2(), kMaxDipoleAm2)) return {"m_body_Am2", "beyond 1e4 A m^2"};
  return {};
}
Breach rangeOf(const msg::ThrusterCmd& s) {
  if (s.thruster_count() > s.on_time_s().size()) return {"thruster_count", "more thrusters than the type holds"};
  if (!nonNegativeWithin(s.on_time_s(), kMaxDurationS)) return {"on_time_s", "negative or beyond 1e5 s"};
  return {};
}
Breach rangeOf(const msg::StationKeepingPlan& s) {
  if (s.firing_count() > s.duration_s().size()) return {"firing_count", "more firings than the type holds"};
  if (!nonNegativeWithin(s.duration_s(), kMaxDurationS)) return {"duration_s", "negative or beyond 1e5 s"};
  return {};
}
Breach rangeOf(const msg::StepGrant& s) {
  if (s.step_period_ns() <= 0) return {"step_period_ns", "not > 0"};
  return {};
}
// Commands are held to their actuators' limits by their consumer, which
// counts each (commands_clamped): only a value that is not finite breaks them.
template <class Sample>
Breach rangeOf(const Sample&) {
  return {};
}

template <class Array>
void zero(Array& a) {
  a.fill({});
}

/// Every field back to its default (zero, false), the header kept.
template <class Sample>
void clearKeepingHeader(Sample& s) {
  const msg::SampleHeader header = s.header();
  s = Sample{};
  s.header(header);
}

// The missing form of each topic (SampleChecks.hpp).
bool missing(msg::MagnetometerReading& s) {
  zero(s.b_body_T());
  s.saturated(false);
  s.valid(false);
  return true;
}
bool missing(msg::SunSensorReading& s) {
  zero(s.sun_body_unit());
  zero(s.cell_output());  // no cell sees the Sun
  s.cell_count(std::min<std::uint32_t>(s.cell_count(), s.cell_output().size()));
  s.valid(false);
  return true;
}
bool missing(msg::GyroReading& s) {
  zero(s.w_body_rad_s());
  s.valid(false);
  return true;
}
bool missing(msg::StarTrackerReading& s) {
  s.q_inertial_body() = {1.0, 0.0, 0.0, 0.0};
  s.valid(false);
  return true;
}
bool missing(msg::WheelTachReading& s) {
  zero(s.wheel_speed_rad_s());
  s.valid(false);
  return true;
}
bool missing(msg::AttitudeEstimate& s) {
  clearKeepingHeader(s);
  s.q_inertial_body() = {1.0, 0.0, 0.0, 0.0};  // consumers act only on a valid estimate
  return true;
}
bool missing(msg::FieldEstimate& s) {
  clearKeepingHeader(s);
  return true;
}
bool missing(msg::CoilRequest& s) {  // nothing asked
  clearKeepingHeader(s);
  return true;
}
bool missing(msg::CoilWindow& s) {  // no window: the owner's own law drives the coils
  clearKeepingHeader(s);
  return true;
}
bool missing(msg::WheelTorqueCmd& s) {  // no torque
  clearKeepingHeader(s);
  return true;
}
bool missing(msg::DipoleCmd& s) {  // coils off
  clearKeepingHeader(s);
  return true;
}
bool missing(msg::FlapCmd& s) {  // flaps neutral
  clearKeepingHeader(s);
  s.split(255);
  return true;
}
bool missing(msg::ThrusterCmd& s) {  // no firing, gimbals at rest
  const auto count = std::min<std::uint32_t>(s.thruster_count(), s.on_time_s().size());
  clearKeepingHeader(s);
  s.thruster_count(count);
  return true;
}
bool missing(msg::StationKeepingPlan& s) {  // a plan with no firings
  clearKeepingHeader(s);
  return true;
}
template <class Sample>
bool missing(Sample&) {
  return false;
}

}  // namespace

template <class Sample>
Breach breachOf(const Sample& sample) {
  if (const char* field = msg::firstNonFinite(sample)) return {field, "not finite"};
  return rangeOf(sample);
}

template <class Sample>
bool takeAsMissing(Sample& sample) {
  return missing(sample);
}

// Every registry topic's type; a type missing here fails to link.
#define FLATSAT_SAMPLE_CHECKS(Type)             \
  template Breach breachOf(const msg::Type&);   \
  template bool takeAsMissing(msg::Type&);
FLATSAT_SAMPLE_CHECKS(StepGrant)
FLATSAT_SAMPLE_CHECKS(StepDone)
FLATSAT_SAMPLE_CHECKS(TruthState)
FLATSAT_SAMPLE_CHECKS(MagnetometerReading)
FLATSAT_SAMPLE_CHECKS(SunSensorReading)
FLATSAT_SAMPLE_CHECKS(GyroReading)
FLATSAT_SAMPLE_CHECKS(StarTrackerReading)
FLATSAT_SAMPLE_CHECKS(WheelTachReading)
FLATSAT_SAMPLE_CHECKS(AttitudeEstimate)
FLATSAT_SAMPLE_CHECKS(FieldEstimate)
FLATSAT_SAMPLE_CHECKS(CoilRequest)
FLATSAT_SAMPLE_CHECKS(CoilWindow)
FLATSAT_SAMPLE_CHECKS(WheelTorqueCmd)
FLATSAT_SAMPLE_CHECKS(DipoleCmd)
FLATSAT_SAMPLE_CHECKS(FlapCmd)
FLATSAT_SAMPLE_CHECKS(ThrusterCmd)
FLATSAT_SAMPLE_CHECKS(StationKeepingPlan)
FLATSAT_SAMPLE_CHECKS(Health)
FLATSAT_SAMPLE_CHECKS(FaultCmd)
FLATSAT_SAMPLE_CHECKS(FaultEvent)
FLATSAT_SAMPLE_CHECKS(BusDelivery)
FLATSAT_SAMPLE_CHECKS(ModeCmd)
FLATSAT_SAMPLE_CHECKS(ParamCmd)
FLATSAT_SAMPLE_CHECKS(CommandAck)
FLATSAT_SAMPLE_CHECKS(ParamState)
#undef FLATSAT_SAMPLE_CHECKS

}  // namespace flatsat::bus
