// SPDX-License-Identifier: Apache-2.0
// DynamicsModel with the environment options: spherical-harmonic field, density
// models, the numerical orbit (with thrust) and the geodetic truth.
#include <cmath>
#include <cstring>
#include <string>

#include <catch2/catch.hpp>

#include "sim/Attitude.hpp"
#include "sim/DynamicsModel.hpp"
#include "sim/SunEphemeris.hpp"
#include "tests/support/ReferenceData.hpp"
#include "tests/support/TestUnits.hpp"
#include "tests/unit/sim/AllocationCounter.hpp"
#include "tests/unit/sim/PyramidWheels.hpp"

using namespace flatsat::sim;
using Catch::Matchers::Contains;

namespace {

using test::kStep;

// A 560 km, 53° orbit; a 1 m cube of six panels with its centre of pressure
// 5 cm off the centre of mass; four wheels.
DynamicsParams boxSat() {
  DynamicsParams p;
  p.epoch = UtcEpoch{2026, 3, 20, 6, 0, 0.0};
  p.orbit = OrbitElements{kEarthEquatorialRadius_m + 560e3, 0.001, 53.0 * kDeg, 40.0 * kDeg, 0.0, 0.0};
  p.body.J_B_kg_m2 = Eigen::Vector3d(20.0, 25.0, 30.0).asDiagonal();
  test::fitPyramidWheels(p.body);
  p.field = igrfDipoleAt(kIgrfFile, decimalYear(p.epoch));
  p.torquer_max_dipole_Am2 = Eigen::Vector3d::Constant(2.0);
  p.q0_NB = quatFromRotationVector(Eigen::Vector3d(0.3, -0.4, 1.2));
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      Panel face;
      face.area_m2 = 1.0;
      face.normal_B = sign * Eigen::Vector3d::Unit(axis);
      face.r_cp_B_m = 0.5 * face.normal_B + Eigen::Vector3d(0.05, 0.0, 0.0);
      p.panels.push_back(face);
    }
  }
  p.orbit_track.forces.mass_kg = 100.0;
  p.orbit_track.forces.drag_area_m2 = 1.2;
  p.orbit_track.forces.srp_area_m2 = 1.2;
  return p;
}

DynamicsParams everyModel() {
  DynamicsParams p = boxSat();
  p.field_model = FieldModel::kSphericalHarmonics;
  p.field_harmonics = igrf14Coefficients(kIgrfFile, decimalYear(p.epoch));
  p.atmosphere = AtmosphereParams{};
  p.orbit_track.propagator = OrbitPropagation::kNumerical;
  p.residual_dipole_B_Am2 = Eigen::Vector3d(0.1, -0.2, 0.05);
  p.body.wheel_viscous_friction_Nms_rad.setConstant(1e-6);
  p.body.wheel_coulomb_friction_Nm.setConstant(1e-5);
  ThrusterParams thruster;
  thruster.r_B_m = Eigen::Vector3d(-0.5, 0.0, 0.0);
  thruster.thrust_N = 1.0;
  p.thrusters = {thruster};
  return p;
}

double jdUt1(const DynamicsParams& p, const Truth& truth) { return julianDate(p.epoch) + toSeconds(truth.t) / 86400.0; }

}  // namespace

TEST_CASE("DynamicsModel evaluates the spherical-harmonic field at the spacecraft", "[sim][dynamics][geomag]") {
  DynamicsParams p = boxSat();
  p.field_model = FieldModel::kSphericalHarmonics;
  p.field_harmonics = igrf14Coefficients(kIgrfFile, decimalYear(p.epoch));
  REQUIRE(p.field_harmonics.degree == 13);
  DynamicsModel model(p);
  for (int k = 1; k <= 20; ++k) model.step(ActuatorCommands{}, k * kStep);
  const Truth& t = model.truth();

  THEN("b_N is IGRF-14 of degree 13 at the truth's position and time, b_B its body view") {
    const Eigen::Vector3d expected = SphericalHarmonicField(p.field_harmonics).b_N_T(t.r_N_m, jdUt1(p, t));
    CHECK((t.b_N_T - expected).norm() < 1e-12 * expected.norm());
    CHECK((t.b_B_T - t.q_NB.conjugate() * t.b_N_T).norm() < 1e-12 * expected.norm());
  }
  WHEN("the degree is cut to 1") {
    p.field_degree = 1;
    DynamicsModel dipole(p);
    for (int k = 1; k <= 20; ++k) dipole.step(ActuatorCommands{}, k * kStep);
    const Truth& d = dipole.truth();
    THEN("the field is the tilted dipole of the same coefficients") {
      const Eigen::Matrix3d R = R_EN(jdUt1(p, d));
      const Eigen::Vector3d expected = R.transpose() * TiltedDipoleField(p.field).b_E_T(R * d.r_N_m);
      CHECK((d.b_N_T - expected).norm() < 1e-12 * expected.norm());
      CHECK((d.b_N_T - t.b_N_T).norm() > 500e-9);  // the higher degrees matter at 560 km
    }
  }
}

TEST_CASE("DynamicsModel takes the air density from the atmosphere model", "[sim][dynamics][atmosphere]") {
  DynamicsParams p = boxSat();
  p.atmosphere = AtmosphereParams{};
  GIVEN("Harris–Priester") {
    DynamicsModel model(p);
    model.step(ActuatorCommands{}, kStep);
    const Truth& t = model.truth();
    const double jd_tt = julianDate(p.epoch) + (0.1 + kTtMinusUtc_s) / 86400.0;
    const double expected = Atmosphere(*p.atmosphere).density_kg_m3(t.r_N_m, sunPosition_N_m(jd_tt).normalized());
    CHECK(t.density_kg_m3 == Approx(expected).epsilon(1e-12));
    CHECK(t.density_kg_m3 > 1e-13);  // 560 km: 1.5e-13 (night) to 1.0e-12 (bulge) kg/m³
    CHECK(t.density_kg_m3 < 1.1e-12);
    THEN("the panels' drag uses it") {
      const ForceTorque aero = aerodynamicForceTorque(p.panels, t.density_kg_m3, t.wind_B_m_s);
      CHECK((t.f_aerodynamic_B_N - aero.force_B_N).norm() < 1e-9 * aero.force_B_N.norm());
      CHECK((t.tau_aerodynamic_B_Nm - aero.torque_B_Nm).norm() < 1e-9 * aero.torque_B_Nm.norm());
    }
  }
  GIVEN("the exponential model") {
    p.atmosphere->model = DensityModel::kExponential;
    DynamicsModel model(p);
    CHECK(model.truth().density_kg_m3 ==
          Approx(exponentialDensity_kg_m3(approximateHeight_m(model.truth().r_N_m))).epsilon(1e-12));
  }
}

TEST_CASE("DynamicsModel flies the numerical orbit and reports the geodetic position", "[sim][dynamics][orbit]") {
  DynamicsParams p = boxSat();
  p.orbit_track.propagator = OrbitPropagation::kNumerical;
  OrbitForceParams& f = p.orbit_track.forces;
  f.j3 = f.j4 = f.drag = f.solar_pressure = f.sun_gravity = f.moon_gravity = false;  // J2 only
  DynamicsModel model(p);
  OrbitPropagator reference(f, p.epoch, KeplerOrbit(p.orbit).at(0.0));
  for (int k = 1; k <= 1000; ++k) model.step(ActuatorCommands{}, k * kStep);
  for (int j = 0; j < 10; ++j) reference.step(10.0);
  const Truth& t = model.truth();

  THEN("at a grid point the truth is the propagator's state") {
    CHECK((t.r_N_m - reference.state().r_N_m).norm() < 1e-6);
    CHECK((t.v_N_m_s - reference.state().v_N_m_s).norm() < 1e-9);
    CHECK((t.r_N_m - KeplerOrbit(p.orbit).at(100.0).r_N_m).norm() > 10.0);  // J2 acts
  }
  THEN("the geodetic position is that of the Earth-fixed position") {
    const GeodeticPosition g = geodeticFromEarthFixed(R_EN(jdUt1(p, t)) * t.r_N_m);
    CHECK(t.geodetic.latitude_rad == g.latitude_rad);
    CHECK(t.geodetic.longitude_rad == g.longitude_rad);
    CHECK(t.geodetic.height_m == g.height_m);
    CHECK(t.geodetic.height_m == Approx(560e3).margin(25e3));
    CHECK(std::abs(t.geodetic.latitude_rad) <= 53.2 * kDeg);
  }
}

TEST_CASE("DynamicsModel: thrust moves the numerical orbit, not the Kepler one", "[sim][dynamics][actuators]") {
  DynamicsParams p = boxSat();
  p.gravity_gradient = false;
  p.panels.clear();
  ThrusterParams thruster;  // through the centre of mass, along body x
  thruster.thrust_N = 2.0;
  p.thrusters = {thruster};
  ActuatorCommands burn;
  burn.thruster_on_time_s(0) = 0.1;  // the whole step
  const auto fly = [&](const DynamicsParams& params, bool fire) {
    DynamicsModel model(params);
    for (int k = 1; k <= 50; ++k) model.step(fire ? burn : ActuatorCommands{}, k * kStep);
    return model.truth();
  };
  // 5 s at 2 N on 100 kg: Δv = 0.1 m/s along the (fixed) body x axis.
  const Eigen::Vector3d dv_expected = p.q0_NB * Eigen::Vector3d(0.1, 0.0, 0.0);
  GIVEN("the numerical orbit") {
    p.orbit_track.propagator = OrbitPropagation::kNumerical;
    p.orbit_track.forces.drag = false;
    const Truth fired = fly(p, true);
    const Truth coasted = fly(p, false);
    CHECK(((fired.v_N_m_s - coasted.v_N_m_s) - dv_expected).norm() < 1e-3 * dv_expected.norm());
    CHECK(((fired.r_N_m - coasted.r_N_m) - 2.5 * dv_expected).norm() < 1e-2 * 2.5 * dv_expected.norm());
    CHECK(fired.f_thruster_B_N == Eigen::Vector3d(2.0, 0.0, 0.0));
  }
  GIVEN("the Kepler orbit") {
    CHECK(fly(p, true).v_N_m_s == fly(p, false).v_N_m_s);
  }
}

TEST_CASE("DynamicsParams::validate checks the environment options", "[sim][dynamics]") {
  DynamicsParams p = everyModel();
  CHECK(p.validate().empty());
  p.field_degree = 14;
  p.atmosphere->bulge_exponent = 9.0;
  p.orbit_track.step_s = 0.0;
  auto errors = p.validate();
  CHECK(errors.size() == 3);
  CHECK(anyStartsWith(errors, "field_degree: 14 must be in 1..13"));
  CHECK(anyStartsWith(errors, "atmosphere.bulge_exponent: "));
  CHECK(anyStartsWith(errors, "orbit_track.step_s: "));

  DynamicsParams empty = everyModel();
  empty.field_harmonics = GaussCoefficients{};
  empty.atmosphere.reset();
  errors = empty.validate();
  CHECK(anyStartsWith(errors, "field_harmonics: no coefficients (g10 = 0)"));
  CHECK(anyStartsWith(errors, "orbit_track.forces.drag: needs an atmosphere model"));
  CHECK_THROWS_WITH(DynamicsModel(empty), Contains("field_harmonics") && Contains("orbit_track.forces.drag"));
}

TEST_CASE("DynamicsModel with every environment model is deterministic and allocation-free",
          "[sim][dynamics][actuators]") {
  const auto command = [](int k) {
    ActuatorCommands cmd;
    cmd.wheel_torque_Nm = 0.005 * Eigen::Vector4d(std::sin(0.01 * k), std::cos(0.013 * k), -0.2, 0.3);
    cmd.dipole_B_Am2 = Eigen::Vector3d(std::cos(0.002 * k), std::sin(0.003 * k), -0.5);
    cmd.thruster_on_time_s(0) = k % 7 == 0 ? 0.05 : 0.0;
    return cmd;
  };
  DynamicsModel first(everyModel());
  DynamicsModel second(everyModel());
  const long long counter_check = test::allocationCount();
  CHECK(std::string(100, 'x').size() == 100);  // one heap allocation, seen by the counter
  REQUIRE(test::allocationCount() > counter_check);
  const long long allocations_before = test::allocationCount();
  for (int k = 1; k <= 600; ++k) {  // 60 s: six orbit grid intervals, thrust kicks
    first.step(command(k), k * kStep);
    second.step(command(k), k * kStep);
  }
  const long long allocations = test::allocationCount() - allocations_before;
  CHECK(allocations == 0);
  const Truth& a = first.truth();
  const Truth& b = second.truth();
  CHECK(std::memcmp(a.q_NB.coeffs().data(), b.q_NB.coeffs().data(), 4 * sizeof(double)) == 0);
  CHECK(std::memcmp(a.r_N_m.data(), b.r_N_m.data(), 3 * sizeof(double)) == 0);
  CHECK(std::memcmp(a.b_N_T.data(), b.b_N_T.data(), 3 * sizeof(double)) == 0);
  CHECK(a.density_kg_m3 == b.density_kg_m3);

  WHEN("reset and run again") {
    const Truth end = first.truth();
    first.reset();
    for (int k = 1; k <= 600; ++k) first.step(command(k), k * kStep);
    CHECK(std::memcmp(first.truth().r_N_m.data(), end.r_N_m.data(), 3 * sizeof(double)) == 0);
    CHECK(std::memcmp(first.truth().w_NB_B_rad_s.data(), end.w_NB_B_rad_s.data(), 3 * sizeof(double)) == 0);
  }
}
