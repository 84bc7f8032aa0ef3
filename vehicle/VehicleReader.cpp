// SPDX-License-Identifier: Apache-2.0
#include "bus/InstallPaths.hpp"
#include "vehicle/VehicleReader.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "bus/FaultFields.hpp"
#include "sim/Constants.hpp"
#include "sim/SphericalHarmonicField.hpp"
#include "vehicle/ReaderSections.hpp"

namespace flatsat::vehicle {

const std::vector<std::string> kEnvironmentKeys = {
    "field_model", "field_degree", "igrf_file", "wmm_file", "atmosphere", "bulge_exponent",
    "harris_priester_table", "density_kg_m3"};

namespace {

namespace fs = std::filesystem;

std::string findDataFile(const bus::Scenario& scenario, const std::string& name) {
  return bus::findBesideOrIn(scenario.file, name, bus::dataDirs());
}

/// orbit.propagator, orbit.step_s and the force switches orbit.forces.*; the
/// spacecraft's mass and areas are read with the spacecraft.
void readPropagator(bus::ParamReader& orbit, sim::OrbitTrackParams& track) {
  std::string propagator = "kepler";
  orbit.read("propagator", propagator);
  if (propagator == "numerical") {
    track.propagator = sim::OrbitPropagation::kNumerical;
  } else if (propagator != "kepler") {
    orbit.problem("propagator", "'" + propagator + "' is neither kepler nor numerical");
  }
  orbit.read("step_s", track.step_s, "s");
  auto forces = orbit.section("forces");
  sim::OrbitForceParams& f = track.forces;
  forces.read("j2", f.j2);
  forces.read("j3", f.j3);
  forces.read("j4", f.j4);
  forces.read("j22", f.j22);
  forces.read("drag", f.drag);
  forces.read("solar_pressure", f.solar_pressure);
  forces.read("sun_gravity", f.sun_gravity);
  forces.read("moon_gravity", f.moon_gravity);
  forces.finish();
  if (track.propagator == sim::OrbitPropagation::kKepler) {
    for (const char* key : {"step_s", "forces"}) {
      if (orbit.has(key)) orbit.problem(key, "only with propagator: numerical");
    }
  }
  // The forces' errors are the spacecraft's (mass, areas, coefficients).
  for (const std::string& error : track.validate()) {
    if (error.rfind("forces.", 0) != 0) orbit.problems({error});
  }
}

/// The six elements, each kept when absent (the onboard view's starts from the truth's).
void readElements(bus::ParamReader& orbit, sim::OrbitElements& elements) {
  double altitude_m = 0.0;
  orbit.read("altitude_m", altitude_m, "m");
  orbit.read("semi_major_axis_m", elements.semi_major_axis_m, "m");
  if (orbit.has("altitude_m") && orbit.has("semi_major_axis_m")) {
    orbit.problem("", "give altitude_m (circular) or semi_major_axis_m, not both");
  } else if (orbit.failed("altitude_m")) {
    orbit.excuse("semi_major_axis_m");
  } else if (orbit.has("altitude_m")) {
    elements.semi_major_axis_m = sim::kEarthEquatorialRadius_m + altitude_m;
  }
  orbit.read("eccentricity", elements.eccentricity, "-");
  orbit.read("inclination_rad", elements.inclination_rad, "rad");
  orbit.read("raan_rad", elements.raan_rad, "rad");
  orbit.read("arg_perigee_rad", elements.arg_perigee_rad, "rad");
  orbit.read("mean_anomaly_rad", elements.mean_anomaly_rad, "rad");
  orbit.problems(elements.validate());
}

/// orbit.station_longitude_deg: a geostationary slot, the one key that places
/// the satellite (a near-circular, near-equatorial orbit is over the Earth-fixed
/// longitude Ω + ω + M − GMST, so M follows) and that station keeping holds.
void readStation(bus::ParamReader& orbit, VehicleDescription& v) {
  constexpr double kDegToRad = std::numbers::pi / 180.0;
  double longitude_deg = 0.0;
  orbit.read("station_longitude_deg", longitude_deg, "deg");
  if (!orbit.has("station_longitude_deg")) return;
  if (orbit.has("mean_anomaly_rad")) {
    orbit.problem("station_longitude_deg", "give it or mean_anomaly_rad, not both: it sets the mean anomaly");
  } else if (!(std::abs(longitude_deg) <= 180.0)) {
    orbit.problem("station_longitude_deg", "outside [-180, 180] deg");
  } else if (!(v.orbit.inclination_rad <= 1.0 * kDegToRad && v.orbit.eccentricity <= 0.01)) {
    orbit.problem("station_longitude_deg", "a slot needs a near-geostationary orbit: inclination_rad <= 1 deg, "
                                           "eccentricity <= 0.01");
  } else {
    v.station_longitude_rad = longitude_deg * kDegToRad;
    const double m = *v.station_longitude_rad + sim::gmst_rad(sim::julianDate(v.epoch)) - v.orbit.raan_rad -
                     v.orbit.arg_perigee_rad;
    v.orbit.mean_anomaly_rad = m - 2.0 * std::numbers::pi * std::floor(m / (2.0 * std::numbers::pi));
  }
}

void readOrbit(bus::ParamReader orbit, VehicleDescription& v) {
  std::string epoch = "2026-03-20T00:00:00Z";
  orbit.read("epoch_utc", epoch);
  try {
    v.epoch = sim::parseIso8601Utc(epoch);
  } catch (const std::invalid_argument& e) {
    orbit.problem("epoch_utc", e.what());
  }
  if (!orbit.has("altitude_m") && !orbit.has("semi_major_axis_m")) {
    orbit.problem("", "give exactly one of altitude_m (circular) or semi_major_axis_m");
  }
  readElements(orbit, v.orbit);
  readStation(orbit, v);
  readPropagator(orbit, v.orbit_track);
  orbit.finish();
}

/// The data files the field models come from, and the keys that named them.
struct FieldFiles {
  std::string igrf = "igrf/igrf14coeffs.txt";
  std::string wmm = "wmm/WMM2025.COF";
  std::string igrf_key = "igrf_file";  ///< where a problem of the file is reported
  std::string wmm_key = "wmm_file";
};

/// `model` (tilted_dipole, igrf14, wmm2025; onboard also spot) at the epoch's decimal year into
/// `field`; problems go to `reader`, an unknown model at `model_key`. The
/// tilted dipole's coefficients always come from the IGRF file.
void loadField(const bus::Scenario& scenario, bus::ParamReader& reader, const std::string& model_key,
               const std::string& model, const FieldFiles& files, const sim::UtcEpoch& epoch, bool onboard,
               FieldModel& field) {
  const double year = sim::decimalYear(epoch);
  field.spherical_harmonics = false;
  field.spot.reset();
  const auto load = [&](const std::string& key, const std::string& file, auto loader) {
    try {
      field.harmonics = loader(findDataFile(scenario, file), year);
      field.spherical_harmonics = true;
    } catch (const std::exception& e) {
      reader.problem(key, e.what());
    }
  };
  bool igrf_read = false;
  try {
    field.dipole = sim::igrfDipoleAt(findDataFile(scenario, files.igrf), year);
    igrf_read = true;
  } catch (const std::exception& e) {
    reader.problem(files.igrf_key, e.what());
  }
  if (model == "igrf14") {
    if (igrf_read) load(files.igrf_key, files.igrf, sim::igrf14Coefficients);
  } else if (model == "wmm2025") {
    load(files.wmm_key, files.wmm, sim::wmm2025Coefficients);
  } else if (model == "spot" && onboard && igrf_read) {
    // Seed S2 claim 5: Bx = −B0 cos u, Bz = −2 B0 sin u in its orbit frame (polar orbit).
    field.spot = sim::SpotFieldModel::firstHarmonic(-field.dipole.g10_nT * 1e-9, sim::kIgrfReferenceRadius_m);
  } else if (model == "spot" && !onboard) {
    reader.problem(model_key, "spot is a model flight software carries (onboard.field_model), not a plant's");
  } else if (model != "tilted_dipole" && model != "spot") {
    reader.problem(model_key, "'" + model + "' is not tilted_dipole, igrf14, wmm2025 or (onboard) spot");
  }
}

void readDegree(bus::ParamReader& reader, FieldModel& field) {
  reader.read("field_degree", field.degree);
  if (field.degree < 1 || field.degree > sim::GaussCoefficients::kMaxDegree) {
    reader.problem("field_degree", std::to_string(field.degree) + " must be in 1..13");
  }
}

/// environment.atmosphere: constant (density_kg_m3) or a density model.
void readAtmosphere(const bus::Scenario& scenario, bus::ParamReader& environment, VehicleDescription& v) {
  std::string model = "constant";
  environment.read("atmosphere", model);
  sim::AtmosphereParams atmosphere;
  environment.read("bulge_exponent", atmosphere.bulge_exponent, "-");
  // The solar activity: the table published for it (default: mean activity, M&G Table 3.8).
  std::string table_file;
  environment.read("harris_priester_table", table_file);
  if (!table_file.empty()) {
    try {
      atmosphere.harris_priester_table = sim::readHarrisPriesterTable(findDataFile(scenario, table_file));
    } catch (const std::exception& e) {
      environment.problem("harris_priester_table", e.what());
    }
  }
  environment.read("density_kg_m3", v.density_kg_m3, "kg/m^3");
  if (model == "harris_priester" || model == "exponential") {
    atmosphere.model = model == "exponential" ? sim::DensityModel::kExponential : sim::DensityModel::kHarrisPriester;
    environment.problems(atmosphere.validate());
    v.atmosphere = atmosphere;
    if (environment.has("density_kg_m3")) environment.problem("density_kg_m3", "only with atmosphere: constant");
  } else if (model != "constant") {
    environment.problem("atmosphere", "'" + model + "' is not constant, harris_priester or exponential");
  }
  for (const char* key : {"bulge_exponent", "harris_priester_table"}) {
    if (model != "harris_priester" && environment.has(key)) environment.problem(key, "only with atmosphere: harris_priester");
  }
  if (!(v.density_kg_m3 >= 0.0 && std::isfinite(v.density_kg_m3))) {
    environment.problem("density_kg_m3", "must be finite and >= 0");
  }
  const sim::OrbitTrackParams& track = v.orbit_track;
  if (track.propagator == sim::OrbitPropagation::kNumerical && track.forces.drag && !v.atmosphere) {
    environment.problem("atmosphere", "the numerical orbit's drag needs harris_priester or exponential");
  }
}

/// onboard.spot_harmonics: `first`, the seed's first harmonic (claim 5), or `odd`, its
/// improved model: harmonics 1, 3 and 5 of IGRF's zonal part along the onboard orbit.
void readSpotHarmonics(const bus::Scenario& scenario, bus::ParamReader& onboard, const FieldFiles& files,
                       double coefficients_year, VehicleDescription& v) {
  std::string harmonics = "first";
  onboard.read("spot_harmonics", harmonics);
  if (!v.field.spot || harmonics == "first") return;
  if (harmonics != "odd") {
    onboard.problem("spot_harmonics", "'" + harmonics + "' is neither first nor odd (harmonics 1, 3 and 5)");
    return;
  }
  try {
    const sim::SphericalHarmonicField igrf = sim::igrf14(findDataFile(scenario, files.igrf), coefficients_year);
    v.field.spot = sim::SpotFieldModel::zonalHarmonics(igrf, v.orbit.semi_major_axis_m, v.orbit.inclination_rad, {1, 3, 5});
  } catch (const std::exception& e) {
    onboard.problem("spot_harmonics", e.what());
  }
}

/// `onboard:`: what flight software believes where it differs from the truth.
/// Each item is checked only where the section gives it: the truth's own
/// problems are reported once, at the truth's keys.
void readOnboard(const bus::Scenario& scenario, bus::ParamReader onboard, const FieldFiles& files,
                 const std::string& truth_model, VehicleDescription& v) {
  onboard.read("inertia_kg_m2", v.body.J_B_kg_m2, "kg m^2");
  auto wheels = onboard.section("wheels");
  int count = v.body.wheel_count;
  wheels.read("axes_body", v.body.wheel_axes_B, count);
  // A list that does not read leaves the count as it was: its own problem says why.
  if (count != v.body.wheel_count) {
    wheels.problem("axes_body", std::to_string(count) + " axes for " + std::to_string(v.body.wheel_count) +
                                    " wheels (spacecraft.wheels)");
  }
  wheels.finish();
  if (onboard.has("inertia_kg_m2") || onboard.has("wheels")) onboard.problems(v.body.validate());
  if (onboard.has("sensors")) readSensorMountings(onboard.section("sensors"), v.sensors);
  // The orbit first: SPOT's harmonics are taken along it.
  if (onboard.has("orbit")) {
    auto orbit = onboard.section("orbit");
    std::string propagator = "truth";
    orbit.read("propagator", propagator);
    if (propagator == "kepler") {
      // Two-body only; the mass and areas stay the spacecraft's (station keeping's thrust).
      v.orbit_track.propagator = sim::OrbitPropagation::kKepler;
    } else if (propagator != "truth") {
      orbit.problem("propagator", "'" + propagator + "' is neither truth nor kepler");
    }
    readElements(orbit, v.orbit);
    orbit.finish();
  }
  bool spot_model = false;  // asked for, whether or not it loaded
  if (onboard.has("field_model") || onboard.has("field_epoch_utc")) {
    std::string model = truth_model;
    onboard.read("field_model", model);
    spot_model = model == "spot";
    // A table loaded then and never updated: its secular variation stops there.
    sim::UtcEpoch coefficients_epoch = v.epoch;
    std::string coefficients_date;
    onboard.read("field_epoch_utc", coefficients_date);
    if (!coefficients_date.empty()) {
      try {
        coefficients_epoch = sim::parseIso8601Utc(coefficients_date);
      } catch (const std::invalid_argument& e) {
        onboard.problem("field_epoch_utc", e.what());
      }
    }
    FieldFiles named_by_environment = files;
    named_by_environment.igrf_key = named_by_environment.wmm_key = "field_model";
    loadField(scenario, onboard, "field_model", model, named_by_environment, coefficients_epoch, true, v.field);
    readSpotHarmonics(scenario, onboard, files, sim::decimalYear(coefficients_epoch), v);
  }
  if (onboard.has("spot_harmonics") && !spot_model) {
    std::string unused;
    onboard.read("spot_harmonics", unused);
    onboard.problem("spot_harmonics", "only with field_model: spot");
  }
  if (onboard.has("field_degree")) readDegree(onboard, v.field);
  if (onboard.has("faults")) v.faults = readActuatorFaults(onboard, v);
  onboard.finish();
}

}  // namespace

Vehicle readVehicle(const bus::Scenario& scenario, bus::ConfigProblems& problems) {
  const std::size_t problems_before = problems.list().size();
  Vehicle vehicle;
  VehicleDescription& truth = vehicle.truth;
  readOrbit(scenario.section("orbit", problems), truth);
  readSpacecraft(scenario.section("spacecraft", problems), truth);

  auto environment = scenario.section("environment", problems);
  std::string model = "tilted_dipole";
  FieldFiles files;
  environment.read("field_model", model);
  environment.read("igrf_file", files.igrf);
  environment.read("wmm_file", files.wmm);
  loadField(scenario, environment, "field_model", model, files, truth.epoch, false, truth.field);
  readDegree(environment, truth.field);
  readAtmosphere(scenario, environment, truth);
  environment.leave({"gravity_gradient", "disturbance_torque_body_Nm"});  // the dynamics server's
  environment.finish();

  vehicle.onboard = truth;
  readOnboard(scenario, scenario.section("onboard", problems), files, model, vehicle.onboard);
  // The sections report their problems at their keys; what only the whole
  // description shows is reported once they are clean.
  if (problems.list().size() == problems_before) {
    for (const auto& error : truth.validate()) problems.add(scenario.file + ": vehicle: " + error);
    for (const auto& error : vehicle.onboard.validate()) problems.add(scenario.file + ": onboard: " + error);
  }
  return vehicle;
}

Vehicle vehicleOf(const bus::Scenario& scenario) {
  bus::ConfigProblems problems;
  Vehicle vehicle = readVehicle(scenario, problems);
  if (!problems.empty()) throw bus::ScenarioError(problems.joined());
  return vehicle;
}

void refuseMovedKeys(bus::ParamReader& section, const std::vector<std::pair<std::string, std::string>>& moved) {
  for (const auto& [key, now_at] : moved) {
    if (!section.has(key)) continue;
    section.problem(key, "moved to the vehicle's description: give it as " + now_at);
    section.leave({key});
  }
}

std::vector<std::string> toActuatorFault(const msg::FaultCmd& command, int wheels, int thrusters,
                                         sim::ActuatorFault& fault) {
  return bus::faultFromCommand(command, fault, kActuatorFaultKinds, sim::parseActuatorFaultKind,
                               [wheels, thrusters](const sim::ActuatorFault& f) { return f.validate(wheels, thrusters); });
}

}  // namespace flatsat::vehicle
