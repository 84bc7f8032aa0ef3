// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/station_keeping/MeanElements.hpp"
#include "components/station_keeping/StationKeepingPlanner.hpp"
#include "vehicle/VehicleDescription.hpp"

namespace flatsat::station_keeping {

/// A thruster failure the planner learns of: from the scenario's actuator
/// faults or a fault command to the dynamics server (FDIR's report).
struct ThrusterFailure {
  GeoThruster thruster = GeoThruster::kNW;
  std::int64_t start_ns = 0;     ///< [ns] simulated time it begins
  std::int64_t duration_ns = 0;  ///< [ns] 0: for the rest of the run
};

struct StationKeepingNodeParams {
  StationKeepingParams planner;   ///< the station, box and plan (StationKeepingPlanner.hpp)
  MeanElementsParams mean_elements;
  double jd_epoch = 0.0;          ///< [d] Julian date (UTC) of the scenario's t = 0
  double step_s = 1.0;            ///< [s] the planner's step: the span of the truth's mean thrust
  double dump_dv_m_s = 0.02;      ///< [m/s] each firing Table I gives to MD alone (nominal: 22 and 28), [0, 1]
  std::vector<ThrusterFailure> failures;  ///< known at load (components.dynamics_server.faults)
};

/// Seed S3's station-keeping planner on the bus. Each step it takes the
/// spacecraft's state from flatsat/truth (standing in for orbit determination,
/// as ground ranging gives it) and the thrust of the last step (the
/// manoeuvres the orbit determination knows of), feeds the osculating
/// synchronous elements to the mean-element filter, and once a sidereal day
/// plans the next orbit's firings for the state of the thrusters and the
/// season. It publishes the plan in force every step on
/// flatsat/station_keeping_plan; the thruster sequencer flies it.
class StationKeepingNode final : public bus::Component {
 public:
  StationKeepingNode(bus::Bus& bus, bus::NodeOptions options, const StationKeepingNodeParams& params);

 private:
  void step(const bus::StepContext& ctx) override;
  /// The failure in force at `sim_time_ns`: the first thruster failed so far
  /// takes its power-unit pair out (a second pair's failure is beyond Table I).
  PairFailure failureAt(std::int64_t sim_time_ns);

  StationKeepingNodeParams params_;
  StationKeepingPlanner planner_;
  MeanElementsFilter filter_;
  bus::InputOf<bus::topics::kTruth>& truth_ = addInput(bus::topics::kTruth);
  bus::WriterOf<bus::topics::kStationKeepingPlan>& plan_out_ = addOutput(bus::topics::kStationKeepingPlan);
  std::unique_ptr<bus::ReaderOf<bus::topics::kFaultCmd>> fault_commands_;
  std::mutex failures_mutex_;  // fault commands arrive on Fast DDS threads
  std::vector<ThrusterFailure> failures_;
  std::optional<StationKeepingPlan> plan_;
  SynchronousElements mean_;
  std::uint32_t plan_count_ = 0;
  std::uint64_t plan_step_ = 0;
};

/// The slot from orbit.station_longitude_deg (onboard view); components.<name>: the planner's keys, the
/// thrusters' cant and slew (checked against spacecraft.thrusters, which must
/// be the six of the seed in the order NW, NC, NE, SW, SC, SE), thrust and mass
/// from spacecraft, the epoch from orbit.
StationKeepingNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                                    const bus::NodeArgs& args, bus::ConfigProblems& problems);

}  // namespace flatsat::station_keeping
