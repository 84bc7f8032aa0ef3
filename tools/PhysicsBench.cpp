// SPDX-License-Identifier: Apache-2.0
#include "bus/InstallPaths.hpp"
#include "tools/PhysicsBench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include "bus/Scenario.hpp"
#include "sim/SphericalHarmonicField.hpp"
#include "tools/FieldCommand.hpp"
#include "components/dynamics_server/DynamicsServerParams.hpp"
#include "sim/DynamicsModel.hpp"
#include "vehicle/VehicleReader.hpp"

namespace flatsat::tools {
namespace {

constexpr int kBatches = 5;
constexpr int kFieldEvaluations = 20000;
constexpr double kFlight_s = 2000.0;

// The first of `dir/relative` over the installed folders that exists.
std::string firstExisting(const std::string& relative, const std::vector<std::filesystem::path>& dirs) {
  if (const auto found = bus::findIn(dirs, relative)) return found->string();
  throw std::runtime_error("no " + relative + " under " + bus::listOfDirs(dirs));
}

double igrf13FieldMicroseconds() {
  const sim::SphericalHarmonicField igrf =
      sim::igrf14(firstExisting("igrf/igrf14coeffs.txt", bus::dataDirs()), 2026.0);
  if (igrf.coefficients().degree != 13) throw std::runtime_error("IGRF-14 at 2026.0 is not of degree 13");
  double best = std::numeric_limits<double>::infinity();
  for (int batch = 0; batch < kBatches; ++batch) {
    best = std::min(best, fieldEvaluationMicroseconds(igrf, kFieldEvaluations));
  }
  return best;
}

double dynamicsStepMicroseconds() {
  const bus::Scenario scenario = bus::loadScenario(
      firstExisting("default.yaml", bus::scenarioDirs()));
  bus::ConfigProblems problems;
  const vehicle::Vehicle craft = vehicle::readVehicle(scenario, problems);
  const dynamics_server::DynamicsServerParams server = dynamics_server::readParams(scenario, craft, {scenario.file, "dynamics_server", ""}, problems);
  if (!problems.empty()) throw std::runtime_error("default scenario: " + problems.joined());
  sim::DynamicsParams p = server.dynamics;
  sim::OrbitForceParams& f = p.orbit_track.forces;
  f.j2 = f.j3 = f.j4 = f.drag = f.solar_pressure = f.sun_gravity = f.moon_gravity = true;
  p.gravity_gradient = true;
  sim::DynamicsModel model(p);

  const sim::SimTime period = server.step_period_ns;
  const auto steps = static_cast<std::int64_t>(std::llround(kFlight_s / sim::toSeconds(period)));
  sim::ActuatorCommands cmd;  // wheels and torquers busy, as in closed loop
  cmd.wheel_torque_Nm = Eigen::Vector4d(0.01, -0.02, 0.015, -0.005);
  cmd.dipole_B_Am2 = Eigen::Vector3d(20.0, -10.0, 5.0);
  double best = std::numeric_limits<double>::infinity();
  double sink = 0.0;
  for (int batch = 0; batch < kBatches; ++batch) {
    model.reset();
    const auto start = std::chrono::steady_clock::now();
    for (std::int64_t k = 1; k <= steps; ++k) model.step(cmd, k * period);
    const auto stop = std::chrono::steady_clock::now();
    sink += model.truth().w_NB_B_rad_s.x();
    best = std::min(best, std::chrono::duration<double, std::micro>(stop - start).count() / steps);
  }
  volatile double keep = sink;  // the steps' results are used
  (void)keep;
  return best;
}

void printFigure(const char* key, double (*measure)()) {
  double value = std::nan("");
  try {
    value = measure();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s: %s\n", key, e.what());
  }
  std::printf("%s=%.3f\n", key, value);
}

}  // namespace

void printPhysicsBench() {
  printFigure("igrf13_field_us", igrf13FieldMicroseconds);
  printFigure("dynamics_step_us", dynamicsStepMicroseconds);
}

}  // namespace flatsat::tools
