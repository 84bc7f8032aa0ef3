// SPDX-License-Identifier: Apache-2.0
// Seed S3 over the bus: a year of GEO station keeping at 75°E in
// each of the four states, the planner, the sequencer and the dynamics server
// each a component of the rig. What is asked: the box held (longitude
// ±0.05°, inclination 0.05°, eccentricity 2e-4); the firings actually flown
// (read from the recording) those of the seed's Table I for the state and
// season, none in the Earth's shadow; a failure injected mid-run switches the
// plan to its row.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/Csv.hpp"
#include "tests/support/Rig.hpp"
#include "tests/support/Run.hpp"
#include "tests/support/TestDomain.hpp"
#include "tests/support/TestUnits.hpp"

namespace fs = std::filesystem;
using namespace flatsat;

namespace {

/// One row of the seed's Table I (Hughes, JP3299143), restated here from the
/// patent, not taken from the planner: a thruster and where it fires. `sun_anti`:
/// at the Sun's right ascension + 180° instead of a fixed one.
struct Row {
  int thruster;
  double ra_deg;
  bool sun_anti = false;
  bool inclination = false;  // at a node: the plan may turn it off the node (i)
  bool dumps = false;        // momentum dumping (MD): the plan may split it in halves
};

enum class Season { kWinterSpring, kSummerAutumn, kSpringEclipse, kAutumnEclipse };

/// Rows of Table I for a state ("nominal", "22/28", "20/30", "24/26") and season.
std::vector<Row> tableI(const std::string& state, Season season) {
  const bool winter_spring = season == Season::kWinterSpring || season == Season::kSpringEclipse;
  if (state == "nominal") {
    return {{20, 90, false, true}, {24, 90, false, true}, {26, 270, false, true}, {30, 270, false, true},
            {22, 90, false, true, true}, {28, 270, false, true, true}};
  }
  if (state == "22/28") {
    if (winter_spring) return {{24, 90, false, true, true}, {26, 270, false, true, true}, {24, 0}, {26, 0}};
    return {{20, 90, false, true, true}, {30, 270, false, true, true}, {20, 180}, {30, 180}};
  }
  std::vector<Row> rows{{22, 90, false, true, true}, {28, 270, false, true, true}};
  const int north = state == "20/30" ? 24 : 20, south = state == "20/30" ? 26 : 30;
  const bool north_at_90_in_spring = state == "20/30";
  if (season == Season::kSpringEclipse || season == Season::kAutumnEclipse) {
    const bool north_at_90 = north_at_90_in_spring == (season == Season::kSpringEclipse);
    rows.push_back({north, north_at_90 ? 90.0 : 270.0});
    rows.push_back({south, north_at_90 ? 270.0 : 90.0});
  } else {
    rows.push_back({north, 0.0, true});
    rows.push_back({south, 0.0, true});
  }
  return rows;
}

/// The seasons the Sun's direction may belong to, with 1.5° of slack at each
/// boundary (the plan is made up to a day before it is flown).
std::set<Season> seasonsOf(double sun_ra_rad, double sun_dec_rad) {
  // The penumbra reaches an equatorial orbit at |δ| < asin(R_E / r) + the Sun's radius: 8.96°.
  const double reach = std::asin(6378137.0 / 42164695.0) + 0.2666 * kDeg;
  std::set<Season> out;
  for (const double dra : {-1.5 * kDeg, 0.0, 1.5 * kDeg}) {
    for (const double ddec : {-1.5 * kDeg, 0.0, 1.5 * kDeg}) {
      const bool winter_spring = std::cos(sun_ra_rad + dra) > 0.0;
      if (std::abs(sun_dec_rad + ddec) < reach) {
        out.insert(winter_spring ? Season::kSpringEclipse : Season::kAutumnEclipse);
      } else {
        out.insert(winter_spring ? Season::kWinterSpring : Season::kSummerAutumn);
      }
    }
  }
  return out;
}

double number(const std::map<std::string, std::string>& row, const std::string& column) {
  const auto at = row.find(column);
  if (at == row.end()) throw std::runtime_error("no column " + column);
  return std::stod(at->second);
}

struct FlownYear {
  nlohmann::json summary;
  std::map<std::uint64_t, std::map<std::string, std::string>> truth;  // by step
  std::vector<std::map<std::string, std::string>> commands;           // thruster_cmd rows
  std::vector<std::map<std::string, std::string>> plans;
};

FlownYear fly(const std::string& scenario, const std::string& extra) {
  test::exportTestDomain();
  const fs::path out = fs::temp_directory_path() / ("flatsat-test-s3-" + std::to_string(::getpid()));
  fs::remove_all(out);
  const std::string bin = std::string(FLATSAT_BIN_DIR) + "/flatsat ";
  const auto run = test::runCommand(bin + "run " + std::string(FLATSAT_SCENARIO_DIR) + "/" + scenario +
                                    " --composed -q --no-plots --out " + out.string() + extra);
  INFO(run.output);
  REQUIRE(run.exit_code == 0);
  const auto exported = test::runCommand(bin + "export --csv -t truth -t thruster_cmd -t station_keeping_plan -o " +
                                         (out / "csv").string() + " " + (out / "recording.sqlite").string());
  INFO(exported.output);
  REQUIRE(exported.exit_code == 0);
  FlownYear year;
  std::ifstream(out / "summary.json") >> year.summary;
  for (auto& row : test::readCsv(out / "csv" / "truth.csv").rows) {
    year.truth[static_cast<std::uint64_t>(number(row, "header.step [-]"))] = std::move(row);
  }
  year.commands = test::readCsv(out / "csv" / "thruster_cmd.csv").rows;
  year.plans = test::readCsv(out / "csv" / "station_keeping_plan.csv").rows;
  fs::remove_all(out);
  return year;
}

/// One thruster's run of recorded steps with on-time.
struct Firing {
  int thruster = 0;
  std::uint64_t first_step = 0, last_step = 0;
  double first_ra = 0.0, last_ra = 0.0;  // [rad] the spacecraft's right ascension at those steps
  double sun_ra = 0.0, sun_dec = 0.0;    // [rad] the Sun's at the first
  int in_shadow = 0;                     // steps in the Earth's shadow, penumbra included
  /// [rad] The arc's middle.
  double centre() const { return first_ra + 0.5 * std::remainder(last_ra - first_ra, 2.0 * std::numbers::pi); }
};

/// The firings, from commands recorded every `interval` steps (the recorder's
/// record_every_steps): a thruster on at two recorded steps that far apart
/// fired throughout.
std::vector<Firing> firingsOf(const FlownYear& year) {
  std::uint64_t interval = std::numeric_limits<std::uint64_t>::max(), previous = 0;
  for (const auto& command : year.commands) {
    const auto step = static_cast<std::uint64_t>(number(command, "header.step [-]"));
    if (step > previous) interval = std::min(interval, step - previous);
    previous = step;
  }
  std::vector<Firing> done;
  std::map<int, Firing> open;  // by thruster
  for (const auto& command : year.commands) {
    const auto step = static_cast<std::uint64_t>(number(command, "header.step [-]"));
    const auto truth = year.truth.find(step);
    if (truth == year.truth.end()) continue;
    const auto& t = truth->second;
    const double ra = std::atan2(number(t, "r_inertial_m[1] [m]"), number(t, "r_inertial_m[0] [m]"));
    for (int i = 0; i < 6; ++i) {
      if (number(command, "on_time_s[" + std::to_string(i) + "] [s]") <= 0.0) continue;
      const int thruster = 20 + 2 * i;
      auto at = open.find(thruster);
      if (at != open.end() && step - at->second.last_step > interval) {
        done.push_back(at->second);
        open.erase(at);
        at = open.end();
      }
      if (at == open.end()) {
        Firing f{thruster, step, step, ra, ra};
        f.sun_ra = std::atan2(number(t, "sun_inertial_unit[1] [-]"), number(t, "sun_inertial_unit[0] [-]"));
        f.sun_dec = std::asin(number(t, "sun_inertial_unit[2] [-]"));
        at = open.emplace(thruster, f).first;
      }
      at->second.last_step = step;
      at->second.last_ra = ra;
      at->second.in_shadow += number(t, "illumination [-]") < 1.0;
    }
  }
  for (const auto& [thruster, f] : open) done.push_back(f);
  return done;
}

/// Every firing flown (read from the recording), checked against Table I: its
/// arc's middle within the planner's documented reach of its row's right
/// ascension: a node's firing turned up to max_ra_shift_rad (0.52 rad,
/// 29.8°), a dumping one split in halves at ± dump_arc_rad (15°), others
/// within 15°. Slack: a day of the Sun's motion for the Sun-fixed rows (the
/// plan is made up to a day before it is flown) and the arc of one recorded
/// interval (10 steps of 60 s: 2.5°) either end. Returns the steps fired in the
/// shadow.
int checkFirings(const FlownYear& year, const std::string& state, std::size_t at_least) {
  constexpr double kSlack_deg = 1.0 + 2.5;
  const auto reach_deg = [](const Row& row) { return row.inclination ? 29.8 + (row.dumps ? 15.0 : 0.0) : 15.0; };
  const auto firings = firingsOf(year);
  int in_shadow = 0;
  double worst_node_deg = 0.0, worst_other_deg = 0.0;
  for (const Firing& f : firings) {
    in_shadow += f.in_shadow;
    double margin_deg = -360.0, off_deg = 360.0;  // of the row it fits best
    bool inclination = false;
    for (const Season season : seasonsOf(f.sun_ra, f.sun_dec)) {
      for (const Row& row : tableI(state, season)) {
        if (row.thruster != f.thruster) continue;
        const double centre = row.sun_anti ? f.sun_ra + std::numbers::pi : row.ra_deg * kDeg;
        const double off = std::abs(std::remainder(f.centre() - centre, 2.0 * std::numbers::pi)) / kDeg;
        const double margin = reach_deg(row) + kSlack_deg - off;
        if (margin > margin_deg) std::tie(margin_deg, off_deg, inclination) = std::tuple(margin, off, row.inclination);
      }
    }
    double& worst = inclination ? worst_node_deg : worst_other_deg;
    worst = std::max(worst, off_deg);
    INFO(state << ": thruster " << f.thruster << " fired steps " << f.first_step << "-" << f.last_step
                << ", arc middle at RA " << f.centre() / kDeg << " deg, " << off_deg << " deg off its row");
    CHECK(margin_deg >= 0.0);
  }
  WARN(state << ": " << firings.size() << " firings; farthest off their row: at the nodes " << worst_node_deg << " deg, elsewhere "
              << worst_other_deg << " deg");
  CHECK(firings.size() >= at_least);
  return in_shadow;
}

}  // namespace

TEST_CASE("S3 in the rig: a year at 75°E in each state holds the box, flying Table I, never in the shadow",
          "[station_keeping][system][s3]") {
  const std::vector<std::pair<std::string, std::string>> states{
      {"geo_nominal.yaml", "nominal"}, {"geo_fail_22_28.yaml", "22/28"},
      {"geo_fail_20_30.yaml", "20/30"}, {"geo_fail_24_26.yaml", "24/26"}};
  for (const auto& [scenario, state] : states) {
    const FlownYear year = fly(scenario, "");
    const auto& s = year.summary;
    INFO(state << ": " << s.dump(2));
    CHECK(s["longitude_dev_deg_max"].get<double>() < 0.05);
    CHECK(s["inclination_deg_max"].get<double>() < 0.05);
    CHECK(s["eccentricity_max"].get<double>() < 2e-4);
    // The inclination alone costs v Δi / cos θ a year: 0.94°/yr in 2027 at
    // 3074.7 m/s and θ = 36° is 62 m/s; a failed pair's firings partly cancel.
    const double inclination_dv = 3074.66 * 0.94 * kDeg / std::cos(36.0 * kDeg);
    CHECK(s["dv_m_s_per_year"].get<double>() > 0.95 * inclination_dv);
    CHECK(s["dv_m_s_per_year"].get<double>() < (state == "nominal" ? 1.25 : 1.7) * inclination_dv);
    // The failed pair never fires; every working thruster of the row does.
    for (const auto& [thruster, count] : s["firings"].items()) {
      const bool failed = state != "nominal" && (thruster.find(state.substr(0, 2)) != std::string::npos ||
                                                 thruster.find(state.substr(3, 2)) != std::string::npos);
      INFO(thruster);
      if (failed) {
        CHECK(count.get<int>() == 0);
      } else {
        CHECK(count.get<int>() > 0);
      }
    }
    CHECK(checkFirings(year, state, 900) == 0);
    // The wings' and the bus's solar pressure (about 1e-5 N m) stays in the
    // wheels only as long as a few days of it: the MD firings' gimbals take
    // it out, and no wheel comes near its limit.
    CHECK(s["wheel_saturation_events"].get<int>() == 0);
    CHECK(s["wheel_momentum_Nms_max"].get<double>() < 0.2 * s["wheel_capacity_Nms"].get<double>());
  }
}

TEST_CASE("S3 in the rig at 19.2°E and 105°E, and the seed's equal centre pair: the box as measured",
          "[station_keeping][system][s3]") {
  // orbit.station_longitude_deg places the satellite over the slot and is
  // the slot station keeping holds. Pinned at 1.5× the measured year
  // (docs/s3_station_keeping.md); at 105°E the box (±0.05°, 0.05°, 2e-4) holds,
  // at 19.2°E the 24/26 failure leaves it by a little. The seed's way for
  // failure mode 2 (centre_pair: equal) holds it at 75°E on 82.5 m/s a year
  // against 99.4 with each sized on its own.
  struct Case {
    std::string scenario, extra;
    double dev_deg, inclination_deg, eccentricity, dv_m_s;
    bool holds_box;
  };
  for (const Case& c : {Case{"geo_nominal.yaml", "--set orbit.station_longitude_deg=105", 0.0158, 0.0134, 1.20e-4, 68.7, true},
                        Case{"geo_fail_24_26.yaml", "--set orbit.station_longitude_deg=19.2", 0.0506, 0.0302, 1.70e-4,
                             103.1, false},
                        Case{"geo_fail_20_30.yaml", "--set components.station_keeping.centre_pair=equal", 0.0292, 0.0218,
                             1.60e-4, 82.5, true}}) {
    const auto out = test::freshDir("s3-slot");
    const auto run = test::runScenario(std::string(FLATSAT_SCENARIO_DIR) + "/" + c.scenario, out, "--composed " + c.extra);
    const auto& s = run.summary;
    INFO(c.scenario << " " << c.extra << ": " << s.dump(2));
    CHECK(s["dv_m_s_per_year"].get<double>() < 1.5 * c.dv_m_s);
    CHECK(s["dv_m_s_per_year"].get<double>() > c.dv_m_s / 1.5);
    CHECK(s["longitude_dev_deg_max"].get<double>() < 1.5 * c.dev_deg);
    CHECK(s["inclination_deg_max"].get<double>() < 1.5 * c.inclination_deg);
    CHECK(s["eccentricity_max"].get<double>() < 1.5 * c.eccentricity);
    if (c.holds_box) {
      CHECK(s["longitude_dev_deg_max"].get<double>() < 0.05);
      CHECK(s["inclination_deg_max"].get<double>() < 0.05);
      CHECK(s["eccentricity_max"].get<double>() < 2e-4);
    }
    CHECK(s["wheel_saturation_events"].get<int>() == 0);
  }
}

TEST_CASE("S3 in the rig: without the MD firings the same torques fill the wheels within the year",
          "[station_keeping][system][s3]") {
  // The nominal state with no MD firing: nothing takes the solar-pressure
  // torque out, and the wheels reach their limit; what bounds them in the
  // case above is the dumping plan.
  const FlownYear year = fly("geo_nominal.yaml", " --set components.station_keeping.dump_dv_m_s=0");
  const auto& s = year.summary;
  INFO(s.dump(2));
  CHECK(s["firings"]["NC(22)"].get<int>() == 0);
  CHECK(s["firings"]["SC(28)"].get<int>() == 0);
  CHECK(s["wheel_momentum_Nms_max"].get<double>() > s["wheel_capacity_Nms"].get<double>());
  CHECK(s["wheel_saturation_events"].get<int>() > 0);
}

TEST_CASE("S3 in the rig: a thruster failing mid-run switches the plan to its pair's row of Table I",
          "[station_keeping][system][s3]") {
  // NE(24) fails on day 3 of a 9-day run: the plans made from then on are the
  // 24/26 row's, and once the last plan made before it has been flown no
  // firing asks for NE(24) or SW(26).
  const double failure_s = 3 * 86400.0;
  const FlownYear run = fly("geo_nominal.yaml",
                            " --set duration_s=777600 --set components.recorder.record_every_steps=1"
                            " --set 'spacecraft.faults=[{kind: thruster_failed, channel: 2, start_s: " +
                                std::to_string(failure_s) + "}]'");
  std::uint64_t first_failed_plan_step = 0;
  for (const auto& plan : run.plans) {
    const double t = 1e-9 * number(plan, "header.sim_time_ns [ns]");
    const int failure = static_cast<int>(number(plan, "failure [-]"));
    CHECK(failure == (t >= failure_s ? 3 : 0));
    if (failure == 3 && number(plan, "plan_count [-]") > 0 && first_failed_plan_step == 0 &&
        number(plan, "plan_step [-]") * 60.0 >= failure_s) {
      first_failed_plan_step = static_cast<std::uint64_t>(number(plan, "plan_step [-]"));
    }
  }
  REQUIRE(first_failed_plan_step > 0);
  FlownYear switched{run.summary, run.truth, {}, {}};
  for (const auto& command : run.commands) {
    // A day on, the burns of the plan made before the failure are over.
    if (number(command, "header.step [-]") >= first_failed_plan_step + 1440) switched.commands.push_back(command);
  }
  for (const auto& command : switched.commands) {
    CHECK(number(command, "on_time_s[2] [s]") == 0.0);  // NE(24)
    CHECK(number(command, "on_time_s[3] [s]") == 0.0);  // SW(26)
  }
  CHECK(checkFirings(switched, "24/26", 14) == 0);
}
