// SPDX-License-Identifier: Apache-2.0
// summary.json from a hand-made recording: every figure that decides a run's
// pass or fail, against the values the samples were made with.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include "analysis/RunFigures.hpp"
#include "analysis/Summary.hpp"
#include "bus/Convert.hpp"
#include "bus/Recording.hpp"
#include "bus/RecordingMeta.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"

using namespace flatsat;

namespace {

constexpr double kDeg = M_PI / 180.0;

struct Workspace {
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("flatsat-summary-" + std::to_string(::getpid()));
  Workspace() { std::filesystem::create_directories(dir); }
  ~Workspace() { std::filesystem::remove_all(dir); }
};

/// A 2 s run over default.yaml: 21 steps of 0.1 s, metrics from 1 s on.
bus::Scenario shortScenario(const Workspace& w) {
  const auto file = w.dir / "short.yaml";
  std::ofstream(file) << "base: " << FLATSAT_SOURCE_DIR << "/deploy/scenarios/default.yaml\n"
                      << "name: short\nduration_orbits: null\nduration_s: 2\nmetrics: {acquisition_s: 1}\n";
  return bus::loadScenario(file.string());
}

template <class Def>
void put(bus::Recording& r, const Def& def, std::uint64_t step, typename Def::Type sample) {
  sample.header().step(step);
  sample.header().sim_time_ns(static_cast<std::int64_t>(step) * 100'000'000);
  r.insert(std::string(def.name), step, std::string(def.producer), sample.header().sim_time_ns(),
           bus::serialize<Def>(sample));
}

}  // namespace

TEST_CASE("summary.json's pointing, momentum, saturation and completion from a hand-made recording",
          "[analysis]") {
  const Workspace w;
  const bus::Scenario scenario = shortScenario(w);
  const std::string path = (w.dir / "recording.sqlite").string();
  // default.yaml's wheels: 0.12 kg m^2, held at 20 N m s.
  const double saturated_rad_s = 20.0 / 0.12;
  {
    bus::Recording r(path, bus::Recording::Access::kCreate);
    for (std::uint64_t k = 0; k <= 20; ++k) {
      msg::TruthState truth;
      // Body x turned θ_k = 0.01 deg·k about z away from the Sun on inertial x.
      bus::put(truth.q_inertial_body(), Eigen::Quaterniond(Eigen::AngleAxisd(0.01 * kDeg * k, Eigen::Vector3d::UnitZ())));
      bus::put(truth.sun_inertial_unit(), Eigen::Vector3d::UnitX());
      bus::put(truth.h_wheels_body_Nms(), Eigen::Vector3d(0.1 * k, 0.0, 0.0));
      truth.wheel_count(4);
      // Wheel 0 at its limit over steps 5..7 and again at 12: two arrivals.
      const bool at_limit = (k >= 5 && k <= 7) || k == 12;
      truth.wheel_speed_rad_s()[0] = at_limit ? -saturated_rad_s : 10.0;
      truth.wheel_cmd_age_steps(k == 3 || k == 9 || k == 15 ? 1 : 0);
      put(r, bus::topics::kTruth, k, truth);
      msg::StepGrant grant;
      grant.final_step(20);
      put(r, bus::topics::kStepGrant, k, grant);
    }
    r.commit();
  }
  analysis::RunOutcome outcome;
  outcome.step_seconds = 0.5;
  outcome.processes = 9;
  const auto s = analysis::summarize(scenario, path, outcome);
  INFO(s.dump(2));
  CHECK(s["completed"] == true);
  CHECK(s["steps"] == 21);
  CHECK(s["sim_seconds"].get<double>() == Approx(2.0));
  CHECK(s["speed_factor"].get<double>() == Approx(4.0));  // 2 s simulated in 0.5 s
  // From 1 s on: θ = 0.10 .. 0.20 deg.
  CHECK(s["pointing_error_deg_max"].get<double>() == Approx(0.20).epsilon(1e-9));
  CHECK(s["pointing_error_deg_mean"].get<double>() == Approx(0.15).epsilon(1e-9));
  CHECK(s["wheel_momentum_Nms_start"].get<double>() == 0.0);
  CHECK(s["wheel_momentum_Nms_max"].get<double>() == Approx(2.0));
  CHECK(s["wheel_momentum_Nms_end"].get<double>() == Approx(2.0));
  CHECK(s["wheel_capacity_Nms"].get<double>() == 20.0);
  CHECK(s["wheel_momentum_fraction_max"].get<double>() == Approx(0.1));
  CHECK(s["wheel_saturation_events"] == 2);
  CHECK(s["wheel_commands_late"] == 3);
}

TEST_CASE("the estimator's figures, accumulated as a recorder stores the samples, are those read back",
          "[analysis]") {
  const Workspace w;
  const bus::Scenario scenario = shortScenario(w);
  // Truth at the identity, the estimate 1 mrad off about x: attitude error
  // θ = 1e-3 rad and NEES θ²/σ², 1 with σ = 1 mrad (steps < 15, inside
  // χ²_3's 95 % bounds) and 100 with σ = 0.1 mrad (steps ≥ 15, outside).
  const double theta = 1e-3;
  const auto record = [&](const std::string& path, bool as_recorder) {
    bus::Recording r(path, bus::Recording::Access::kCreate);
    analysis::RunFigures figures(scenario);
    if (as_recorder) r.observeStored([&figures](const bus::StoredSample& s) { figures.add(s); });
    for (std::uint64_t k = 0; k <= 20; ++k) {
      msg::TruthState truth;
      bus::put(truth.q_inertial_body(), Eigen::Quaterniond::Identity());
      bus::put(truth.sun_inertial_unit(), Eigen::Vector3d::UnitX());
      truth.illumination(k % 2 == 0 ? 1.0 : 0.5);  // sunlit at the even steps only
      msg::AttitudeEstimate estimate;
      bus::put(estimate.q_inertial_body(), Eigen::Quaterniond(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitX())));
      estimate.valid(true);
      estimate.has_covariance(true);
      const double sigma = k < 15 ? 1e-3 : 1e-4;
      for (int i = 0; i < 3; ++i) estimate.attitude_cov_body_rad2()[4 * i] = sigma * sigma;
      estimate.measurements_rejected(k);
      // As samples arrive: the estimate before the truth of its step, or after.
      if (k % 2 == 0) put(r, bus::topics::kAttitudeEstimate, k, estimate);
      put(r, bus::topics::kTruth, k, truth);
      if (k % 2 == 1) put(r, bus::topics::kAttitudeEstimate, k, estimate);
      msg::StepGrant grant;
      grant.final_step(20);
      put(r, bus::topics::kStepGrant, k, grant);
    }
    r.commit();
    if (as_recorder) r.setMeta(bus::meta::kFigures, figures.json());
  };
  const std::string kept_path = (w.dir / "kept.sqlite").string(), read_path = (w.dir / "read.sqlite").string();
  record(kept_path, true);
  record(read_path, false);
  REQUIRE_FALSE(bus::Recording(kept_path, bus::Recording::Access::kRead).meta(bus::meta::kFigures).empty());
  REQUIRE(bus::Recording(read_path, bus::Recording::Access::kRead).meta(bus::meta::kFigures).empty());
  auto kept = analysis::summarize(scenario, kept_path, analysis::RunOutcome{});
  auto read = analysis::summarize(scenario, read_path, analysis::RunOutcome{});
  INFO(kept.dump(2));
  // From 1 s on (steps 10..20): 11 estimates, 5 in bounds, the 6 sunlit ones all θ off.
  CHECK(kept["attitude_error_deg_3sigma"].get<double>() == Approx(3.0 * theta / kDeg).epsilon(1e-9));
  CHECK(kept["nees_in_bounds_fraction"].get<double>() == Approx(5.0 / 11.0).epsilon(1e-12));
  CHECK(kept["estimator_measurements_rejected"] == 20);
  CHECK(kept["completed"] == true);
  CHECK(kept["steps"] == 21);
  kept.erase("recording");
  read.erase("recording");
  CHECK(kept == read);
}

TEST_CASE("a recording that stops short of the final step is not a completed run", "[analysis]") {
  const Workspace w;
  const bus::Scenario scenario = shortScenario(w);
  const std::string path = (w.dir / "recording.sqlite").string();
  {
    bus::Recording r(path, bus::Recording::Access::kCreate);
    for (std::uint64_t k = 0; k <= 12; ++k) {
      msg::StepGrant grant;
      grant.final_step(20);
      put(r, bus::topics::kStepGrant, k, grant);
    }
    r.commit();
  }
  const auto s = analysis::summarize(scenario, path, analysis::RunOutcome{});
  CHECK(s["completed"] == false);
  CHECK(s["end_reason"] == "the recording ends at step 12 of 20");
  // No truth past acquisition_s: the pointing was not measured, which is not a perfect 0.
  CHECK(s["pointing_error_deg_max"].is_null());
  CHECK(s["pointing_error_deg_mean"].is_null());
}

TEST_CASE("the summary table names each ownership switch, and a fleet's summaries as such", "[analysis]") {
  nlohmann::ordered_json summary;
  summary["steps"] = 3001;
  summary["ownership_switches"] = nlohmann::ordered_json::array(
      {{{"time_s", 12.3}, {"topic", "flatsat/magnetometer"}, {"from", "magnetometer"}, {"to", "magnetometer_bridge"},
        {"gap_s", 0.1}}});
  const auto one = flatsat::analysis::summaryTable(summary);
  INFO(one);
  CHECK(one.find("flatsat/magnetometer: magnetometer -> magnetometer_bridge at 12.3 s (gap 0.1 s)") != std::string::npos);
  CHECK(one.find("summaries") == std::string::npos);

  for (int i = 0; i < 4; ++i) summary["ownership_switches"].push_back(summary["ownership_switches"][0]);
  CHECK(flatsat::analysis::summaryTable(summary).find("; 5 in all (summary.json)") != std::string::npos);

  nlohmann::ordered_json fleet;
  fleet["spacecraft"] = nlohmann::ordered_json::array({{{"steps", 1}}, {{"steps", 1}}});
  CHECK(flatsat::analysis::summaryTable(fleet).find("2 summaries (spacecraft-<i>/summary.json)") != std::string::npos);
}
