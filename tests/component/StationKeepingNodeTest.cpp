// SPDX-License-Identifier: Apache-2.0
// The station-keeping node (seed S3) against a scripted time master that flies
// a spacecraft exactly geostationary over the station: once its mean-element
// window is full it plans, and the plan's mean elements are the station's (the
// longitude to 1e-6 rad, no drift, no eccentricity, no inclination); the pair
// failure in force follows the thruster failure the node knows of, from its
// start on.
#include <catch2/catch.hpp>

#include <cmath>

#include "bus/Convert.hpp"
#include "bus/TimeMaster.hpp"
#include "components/station_keeping/StationKeepingNode.hpp"
#include "sim/Constants.hpp"
#include "sim/Time.hpp"
#include "tests/support/FedByScript.hpp"
#include "tests/support/NodeUnderTest.hpp"

namespace {

using namespace flatsat;

constexpr std::uint64_t kSteps = 12;
constexpr std::int64_t kStep_ns = 600'000'000'000;  // 600 s
constexpr double kJdEpoch = 2461119.5;              // 2026-03-20 00:00 UTC
constexpr double kStationLongitude_rad = 75.0 * M_PI / 180.0;
constexpr std::int64_t kFailure_ns = 3 * kStep_ns;  // NC(22) fails at step 3

class GeostationaryScript final : public bus::TimeMaster {
 public:
  GeostationaryScript(bus::Bus& bus, bus::NodeOptions options)
      : TimeMaster(bus, std::move(options), {kStep_ns, kSteps - 1}) {}
  std::map<std::uint64_t, msg::StationKeepingPlan> received;

 private:
  void publishStep(const bus::StepContext& ctx) override {
    // Geostationary radius: the circular orbit whose rate is the Earth's.
    const double radius_m = std::cbrt(sim::kMuEarth_m3_s2 / std::pow(sim::kEarthRotationRate_rad_s, 2));
    const double jd = kJdEpoch + sim::toSeconds(ctx.sim_time_ns) / 86400.0;
    const double ra = sim::gmst_rad(jd) + kStationLongitude_rad;
    const Eigen::Vector3d r(radius_m * std::cos(ra), radius_m * std::sin(ra), 0.0);
    msg::TruthState truth;
    bus::stamp(truth.header(), ctx, "dynamics_server");
    bus::put(truth.q_inertial_body(), Eigen::Quaterniond::Identity());
    bus::put(truth.r_inertial_m(), r);
    bus::put(truth.v_inertial_m_s(), Eigen::Vector3d(0, 0, sim::kEarthRotationRate_rad_s).cross(r));
    truth_.write(truth);
  }
  void advance(const bus::StepContext& ctx) override { received[ctx.step] = plan_.at(ctx.step); }
  bus::WriterOf<bus::topics::kTruth>& truth_ = addOutput(bus::topics::kTruth);
  bus::InputOf<bus::topics::kStationKeepingPlan>& plan_ = addInput(bus::topics::kStationKeepingPlan);
};

}  // namespace

TEST_CASE("station-keeping node plans on the station's mean elements and flies the failed pair's row from its start",
          "[station_keeping][component][dds]") {
  station_keeping::StationKeepingNodeParams params;
  params.planner.station_longitude_rad = kStationLongitude_rad;
  params.mean_elements.window_s = 3600.0;  // six steps
  params.jd_epoch = kJdEpoch;
  params.step_s = 600.0;
  params.failures = {{station_keeping::GeoThruster::kNC, kFailure_ns, 0}};

  const bus::Schedule view = {{"dynamics_server", 1}, {"station_keeping", 1}};
  test::NodeTestBuses buses("station_keeping");
  GeostationaryScript script(buses.script, {"dynamics_server", view});
  station_keeping::StationKeepingNode node(buses.node, test::fedByScript({"station_keeping", view}), params);

  test::runTogether(script, node);

  REQUIRE(script.received.size() == kSteps);
  std::uint32_t plans = 0;
  for (const auto& [k, plan] : script.received) {
    CAPTURE(k);
    CHECK(plan.header().step() == k);
    const auto expected = static_cast<std::int64_t>(k) * kStep_ns >= kFailure_ns
                              ? station_keeping::PairFailure::k22_28
                              : station_keeping::PairFailure::kNone;
    CHECK(plan.failure() == static_cast<std::uint8_t>(expected));
    CHECK(plan.plan_count() >= plans);  // plans are counted, never forgotten
    plans = plan.plan_count();
    if (plan.plan_count() == 0) continue;
    CHECK(plan.mean_longitude_rad() == Approx(kStationLongitude_rad).margin(1e-6));
    CHECK(std::abs(plan.mean_drift_rad_s()) < 1e-10);
    CHECK(std::hypot(plan.mean_e()[0], plan.mean_e()[1]) < 1e-6);
    CHECK(std::hypot(plan.mean_i_rad()[0], plan.mean_i_rad()[1]) < 1e-6);
    CHECK(std::isfinite(plan.dv_total_m_s()));
  }
  CHECK(plans >= 1);
}
