// SPDX-License-Identifier: Apache-2.0
// The vehicle of a scenario: read once, the onboard view equal to the truth
// item by item unless `onboard:` says otherwise, and every problem named by
// file and key.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include "sim/SphericalHarmonicField.hpp"
#include "sim/SpotFieldModel.hpp"
#include "sim/Time.hpp"
#include "vehicle/VehicleReader.hpp"

using namespace flatsat;

namespace {

const std::string kDefault = std::string(FLATSAT_SOURCE_DIR) + "/deploy/scenarios/default.yaml";

/// A scenario laid over default.yaml, in a folder of this process's own.
struct OverDefault {
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("vehicle-reader-" + std::to_string(::getpid()));
  OverDefault() { std::filesystem::create_directories(dir); }
  ~OverDefault() { std::filesystem::remove_all(dir); }
  bus::Scenario load(const std::string& name, const std::string& keys) const {
    const auto file = dir / name;
    std::ofstream(file) << "base: " << kDefault << "\nname: " << name << "\n" << keys;
    return bus::loadScenario(file.string());
  }
};

bool anyContains(const std::vector<std::string>& problems, const std::string& text) {
  for (const auto& p : problems) {
    if (p.find(text) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("the onboard view of a scenario without onboard: is its truth", "[vehicle]") {
  bus::ConfigProblems problems;
  const vehicle::Vehicle v = vehicle::readVehicle(bus::loadScenario(kDefault), problems);
  REQUIRE(problems.list().empty());
  // default.yaml's figures: inertia row 1, 560 km at 53 deg, four wheels, 150 A m^2 coils.
  CHECK(v.truth.body.J_B_kg_m2(0, 0) == 1500.0);
  CHECK(v.truth.body.J_B_kg_m2(0, 1) == 20.0);
  CHECK(v.truth.orbit.semi_major_axis_m == 6378137.0 + 560e3);
  CHECK(v.truth.orbit.inclination_rad == Approx(53.0 * M_PI / 180.0).epsilon(1e-15));
  CHECK(v.truth.body.wheel_count == 4);
  CHECK(v.truth.torquer_max_dipole_Am2 == Eigen::Vector3d::Constant(150.0));
  CHECK(v.truth.field.spherical_harmonics);
  CHECK(v.truth.field.degree == 13);
  // IGRF-14 g10 at the epoch 2026-03-20 (78 days into 2026): -29350.0 nT at 2025.0
  // and +12.6 nT/yr (data/igrf/igrf14coeffs.txt).
  CHECK(v.truth.field.harmonics.g_nT[1][0] == Approx(-29350.0 + 12.6 * (1.0 + 78.0 / 365.0)).margin(0.01));

  CHECK(v.onboard.body.J_B_kg_m2 == v.truth.body.J_B_kg_m2);
  CHECK(v.onboard.body.wheel_axes_B == v.truth.body.wheel_axes_B);
  CHECK(v.onboard.orbit.semi_major_axis_m == v.truth.orbit.semi_major_axis_m);
  CHECK(v.onboard.orbit_track.propagator == v.truth.orbit_track.propagator);
  CHECK(v.onboard.field.harmonics.g_nT[1][0] == v.truth.field.harmonics.g_nT[1][0]);
  CHECK(v.onboard.sensors.sun_sensor_boresight_B == v.truth.sensors.sun_sensor_boresight_B);
  CHECK(v.onboard.faults.size() == v.truth.faults.size());
}

TEST_CASE("onboard: makes model error a setting, item by item", "[vehicle]") {
  const OverDefault over;
  const auto scenario = over.load("misknown.yaml",
                                  "spacecraft:\n"
                                  "  faults: [{kind: wheel_failed, channel: 2, start_s: 600}]\n"
                                  "onboard:\n"
                                  "  inertia_kg_m2: [[1650, 20, -15], [20, 2600, 10], [-15, 10, 2800]]\n"
                                  "  sensors: {star_tracker: {q_body_sensor: [0.9999619230641713, 0.0087265354983739, 0, 0]}}\n"
                                  "  field_model: tilted_dipole\n"
                                  "  orbit: {propagator: kepler, mean_anomaly_rad: 0.01 deg}\n"
                                  "  faults: []\n");
  bus::ConfigProblems problems;
  const vehicle::Vehicle v = vehicle::readVehicle(scenario, problems);
  INFO(problems.joined());
  REQUIRE(problems.list().empty());
  // The truth is as default.yaml has it, with the fault.
  CHECK(v.truth.body.J_B_kg_m2(0, 0) == 1500.0);
  CHECK(v.truth.sensors.q_body_star_tracker.w() == 1.0);
  CHECK(v.truth.field.spherical_harmonics);
  CHECK(v.truth.orbit_track.propagator == sim::OrbitPropagation::kNumerical);
  CHECK(v.truth.orbit.mean_anomaly_rad == 0.0);
  REQUIRE(v.truth.faults.size() == 1);
  CHECK(v.truth.faults[0].start_ns == 600'000'000'000LL);
  // Onboard: 10 % more inertia about x, the star tracker's mounting 1 deg about x,
  // the tilted dipole, a Kepler orbit 0.01 deg ahead, no fault declared.
  CHECK(v.onboard.body.J_B_kg_m2(0, 0) == 1650.0);
  CHECK(v.onboard.body.J_B_kg_m2(1, 1) == 2600.0);
  const double mounting_error_rad =
      v.onboard.sensors.q_body_star_tracker.angularDistance(v.truth.sensors.q_body_star_tracker);
  CHECK(mounting_error_rad == Approx(M_PI / 180.0).epsilon(1e-9));
  CHECK_FALSE(v.onboard.field.spherical_harmonics);
  CHECK(v.onboard.field.dipole.g10_nT == v.truth.field.dipole.g10_nT);
  CHECK(v.onboard.orbit_track.propagator == sim::OrbitPropagation::kKepler);
  CHECK(v.onboard.orbit.mean_anomaly_rad == Approx(0.01 * M_PI / 180.0).epsilon(1e-15));
  CHECK(v.onboard.orbit.semi_major_axis_m == v.truth.orbit.semi_major_axis_m);
  CHECK(v.onboard.orbit_track.forces.mass_kg == 2426.0);  // two-body, but still the spacecraft's mass
  CHECK(v.onboard.faults.empty());
  // Items the view leaves alone stay the truth's.
  CHECK(v.onboard.body.wheel_axes_B == v.truth.body.wheel_axes_B);
  CHECK(v.onboard.torquer_max_dipole_Am2 == v.truth.torquer_max_dipole_Am2);
}

TEST_CASE("a vehicle's problems name the file and the key", "[vehicle]") {
  const OverDefault over;
  const auto scenario = over.load("bad.yaml",
                                  "spacecraft:\n"
                                  "  sensors: {star_tracker: {q_body_sensor: [1, 1, 0, 0]}, sun_sensor: {boresight: [1, 0, 0]}}\n"
                                  "  faults: [{kind: wheel_failed, channel: 7}]\n"
                                  "  flaps: {plate_area_m2: 0.5, lever_arm_m: 2, wings_along: x}\n"
                                  "onboard:\n"
                                  "  wheels: {axes_body: [[1, 0, 0], [0, 1, 0]]}\n"
                                  "  field_model: igrf99\n"
                                  "  orbit: {propagator: numerical}\n");
  bus::ConfigProblems problems;
  vehicle::readVehicle(scenario, problems);
  const auto& list = problems.list();
  INFO(problems.joined());
  CHECK(anyContains(list, "bad.yaml"));
  CHECK(anyContains(list, "spacecraft.sensors.star_tracker.q_body_sensor"));
  CHECK(anyContains(list, "spacecraft.sensors.sun_sensor.boresight: unknown key"));
  CHECK(anyContains(list, "spacecraft.faults[0]"));
  CHECK(anyContains(list, "spacecraft.flaps.wings_along: 'x' is neither y"));
  CHECK(anyContains(list, "onboard.wheels.axes_body: 2 axes for 4 wheels"));
  CHECK(anyContains(list, "onboard.field_model: 'igrf99' is not tilted_dipole, igrf14, wmm2025 or (onboard) spot"));
  CHECK(anyContains(list, "onboard.orbit.propagator: 'numerical' is neither truth nor kepler"));
}

TEST_CASE("onboard.spot_harmonics: the seed's first harmonic, or harmonics 1, 3 and 5 along the onboard orbit",
          "[vehicle]") {
  const OverDefault over;
  bus::ConfigProblems problems;
  const vehicle::Vehicle first = vehicle::readVehicle(over.load("first.yaml", "onboard: {field_model: spot}\n"), problems);
  const vehicle::Vehicle odd = vehicle::readVehicle(
      over.load("odd.yaml", "onboard: {field_model: spot, spot_harmonics: odd, orbit: {inclination_rad: 90 deg}}\n"),
      problems);
  INFO(problems.joined());
  REQUIRE(problems.empty());
  REQUIRE(first.onboard.field.spot.has_value());
  REQUIRE(odd.onboard.field.spot.has_value());
  // The seed's form has harmonic 1 only; the odd model adds 3 and 5 (IGRF's g30, g50 along
  // the polar orbit given onboard) and leaves out the even ones (g20, g40).
  const auto& c1 = first.onboard.field.spot->cosineTerms_T();
  CHECK(c1[3].norm() == 0.0);
  const auto& s_odd = odd.onboard.field.spot->sineTerms_T();
  const auto& c_odd = odd.onboard.field.spot->cosineTerms_T();
  CHECK(s_odd[3].norm() > 1e-7);
  CHECK(s_odd[5].norm() > 1e-9);
  CHECK(c_odd[2].norm() + s_odd[2].norm() + c_odd[0].norm() == 0.0);
  // Taken along the onboard orbit (90 deg), not the truth's (53 deg): off the pole the
  // zonal field has a cross-track part, B_Y = Σ (a/r)^(n+2) g_n0 P_n'(s) cos i.
  const auto igrf = sim::igrf14(std::string(FLATSAT_DATA_DIR) + "/igrf/igrf14coeffs.txt", sim::decimalYear(odd.onboard.epoch));
  const auto along = [&](double inclination_rad) {
    return sim::SpotFieldModel::zonalHarmonics(igrf, odd.onboard.orbit.semi_major_axis_m, inclination_rad, {1, 3, 5});
  };
  for (int k : {1, 3, 5}) {
    CHECK(s_odd[k].isApprox(along(M_PI / 2).sineTerms_T()[k], 1e-12));
    CHECK(c_odd[k].isApprox(along(M_PI / 2).cosineTerms_T()[k], 1e-12));
  }
  CHECK_FALSE(c_odd[1].isApprox(along(odd.truth.orbit.inclination_rad).cosineTerms_T()[1], 1e-3));

  bus::ConfigProblems refused;
  vehicle::readVehicle(over.load("misplaced.yaml", "onboard: {field_model: igrf14, spot_harmonics: odd}\n"), refused);
  vehicle::readVehicle(over.load("unknown.yaml", "onboard: {field_model: spot, spot_harmonics: all}\n"), refused);
  INFO(refused.joined());
  CHECK(anyContains(refused.list(), "misplaced.yaml"));
  CHECK(anyContains(refused.list(), "onboard.spot_harmonics: only with field_model: spot"));
  CHECK(anyContains(refused.list(), "onboard.spot_harmonics: 'all' is neither first nor odd"));
}

TEST_CASE("a problem of the truth is reported once, at its own key, not again for the onboard view", "[vehicle]") {
  const OverDefault over;
  // Inertia breaking the triangle inequality (5 > 1 + 1).
  const auto scenario = over.load("lopsided.yaml", "spacecraft:\n  inertia_kg_m2: [[1, 0, 0], [0, 1, 0], [0, 0, 5]]\n");
  bus::ConfigProblems problems;
  vehicle::readVehicle(scenario, problems);
  INFO(problems.joined());
  REQUIRE(problems.list().size() == 1);
  CHECK(anyContains(problems.list(), "spacecraft"));
  CHECK_FALSE(anyContains(problems.list(), "onboard"));
}

TEST_CASE("orbit.station_longitude_deg places a geostationary satellite over its slot", "[vehicle]") {
  const OverDefault over;
  const auto geo = [](const std::string& inclination, const std::string& more) {
    return "orbit: {altitude_m: 35786 km, inclination_rad: " + inclination +
           ", eccentricity: 0, raan_rad: 10 deg, arg_perigee_rad: 20 deg, epoch_utc: '1992-08-20T12:14:00Z', " + more +
           "}\n";
  };
  bus::ConfigProblems problems;
  const auto v =
      vehicle::readVehicle(over.load("slot.yaml", geo("0", "mean_anomaly_rad: null, station_longitude_deg: -30")), problems);
  INFO(problems.joined());
  REQUIRE(problems.empty());
  // Vallado, Fundamentals of Astrodynamics, Example 3-5: GMST = 152.578 787 886 deg at
  // 1992 Aug 20 12:14 UT1; over -30 deg the right ascension Ω + ω + M is GMST − 30 deg.
  REQUIRE(v.truth.station_longitude_rad);
  CHECK(*v.truth.station_longitude_rad == Approx(-30.0 * M_PI / 180.0));
  CHECK(v.truth.orbit.mean_anomaly_rad * 180.0 / M_PI == Approx(152.578787886 - 30.0 - 10.0 - 20.0).margin(1e-6));
  CHECK(v.onboard.station_longitude_rad == v.truth.station_longitude_rad);

  const auto problemsOf = [&](const std::string& name, const std::string& keys) {
    bus::ConfigProblems found;
    vehicle::readVehicle(over.load(name, keys), found);
    return found.list();
  };
  CHECK(anyContains(problemsOf("both.yaml", geo("0", "mean_anomaly_rad: 1 deg, station_longitude_deg: 5")),
                    "orbit.station_longitude_deg: give it or mean_anomaly_rad, not both"));
  CHECK(anyContains(problemsOf("inclined.yaml", geo("3 deg", "mean_anomaly_rad: null, station_longitude_deg: 5")),
                    "orbit.station_longitude_deg: a slot needs a near-geostationary orbit"));
  CHECK(anyContains(problemsOf("outside.yaml", geo("0", "mean_anomaly_rad: null, station_longitude_deg: 200")),
                    "orbit.station_longitude_deg: outside [-180, 180] deg"));
}

TEST_CASE("onboard.field_epoch_utc: the onboard coefficients as evaluated years before the run", "[vehicle]") {
  const OverDefault over;
  bus::ConfigProblems problems;
  const auto v = vehicle::readVehicle(
      over.load("old_table.yaml", "onboard: {field_epoch_utc: '2020-01-01T00:00:00Z', field_degree: 8}\n"), problems);
  INFO(problems.joined());
  REQUIRE(problems.empty());
  // IGRF-14 g10: -29403.41 nT at 2020.0 (DGRF) (data/igrf/igrf14coeffs.txt), the truth's at the
  // run's epoch as above; the degree the onboard view's own.
  CHECK(v.onboard.field.harmonics.g_nT[1][0] == Approx(-29403.41).margin(0.01));
  CHECK(v.truth.field.harmonics.g_nT[1][0] == Approx(-29350.0 + 12.6 * (1.0 + 78.0 / 365.0)).margin(0.01));
  CHECK(v.onboard.field.degree == 8);
  CHECK(v.truth.field.degree == 13);

  bus::ConfigProblems bad;
  vehicle::readVehicle(over.load("bad_date.yaml", "onboard: {field_epoch_utc: 'last spring'}\n"), bad);
  CHECK(anyContains(bad.list(), "onboard.field_epoch_utc:"));
}

TEST_CASE("a misread altitude is one problem, not a second about the semi-major axis it would set", "[vehicle]") {
  const OverDefault over;
  const auto scenario = over.load("unit.yaml", "orbit:\n  altitude_m: 560 deg\n");
  bus::ConfigProblems problems;
  vehicle::readVehicle(scenario, problems);
  INFO(problems.joined());
  CHECK(anyContains(problems.list(), "orbit.altitude_m: wrong unit 'deg'"));
  CHECK_FALSE(anyContains(problems.list(), "semi_major_axis_m"));
  CHECK(problems.list().size() == 1);
}
