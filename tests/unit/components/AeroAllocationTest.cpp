// SPDX-License-Identifier: Apache-2.0
// Seed S2's split of a demanded torque between the coils and the flaps (algorithms.md S2).
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include "components/unloading_controller/AeroAllocation.hpp"
#include "sim/Flaps.hpp"

using flatsat::unloading_controller::AeroAllocation;
using flatsat::unloading_controller::AeroAllocationInput;
using flatsat::unloading_controller::AeroAllocationOutput;
using flatsat::unloading_controller::AeroAllocationParams;
using flatsat::unloading_controller::AeroSplit;
using flatsat::unloading_controller::FlapInversion;
namespace sim = flatsat::sim;

namespace {

constexpr double kFlapScale_Nm = 1e-4;  // K = 2ρA_pV²l: 1 m² plates, 1 m arm, ρ ~ 1e-12, V 7.7 km/s

AeroAllocationParams wide(AeroSplit split) {
  AeroAllocationParams p;
  p.split = split;
  p.max_dipole_Am2 = Eigen::Vector3d::Constant(1e6);
  return p;
}

/// A polar-orbit-like field: mostly in the orbit (x–z) plane, up to ~20° out of it (seed).
Eigen::Vector3d field(std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
  std::uniform_real_distribution<double> out(-0.35, 0.35);
  const double a = angle(rng);
  return 3e-5 * Eigen::Vector3d(std::cos(a), out(rng), 2.0 * std::sin(a)).normalized();
}

/// A random demand (10 µN m per axis, 1σ) in field b, with the air of kFlapScale_Nm: within
/// the flaps' reach (K = 100 µN m, |c| up to about 1), so that all of it is delivered.
AeroAllocationInput demandIn(const Eigen::Vector3d& b_B_T, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  AeroAllocationInput in;
  in.b_B_T = b_B_T;
  in.c_demand_B_Nm = 1e-5 * Eigen::Vector3d(n(rng), n(rng), n(rng));
  in.flap_scale_Nm = kFlapScale_Nm;
  return in;
}

/// The coils' M × B and the plant's flap torque `c_aero` together give the demand, M ⟂ B (eq. I).
void checkDemandMet(const AeroAllocationInput& in, const AeroAllocationOutput& out, const Eigen::Vector3d& c_aero) {
  const Eigen::Vector3d& B = in.b_B_T;
  const Eigen::Vector3d& C = in.c_demand_B_Nm;
  CHECK((out.m_B_Am2.cross(B) + c_aero - C).norm() < 1e-9 * C.norm());
  CHECK(std::abs(out.m_B_Am2.dot(B)) < 1e-12 * out.m_B_Am2.norm() * B.norm());
}

}  // namespace

TEST_CASE("S2 split: coils and flaps together give the demanded torque with the least flap torque",
          "[unloading_controller][unit][s2]") {
  const AeroAllocation split(wide(AeroSplit::kMagneticAero));
  std::mt19937 rng(7);
  for (int k = 0; k < 2000; ++k) {
    const AeroAllocationInput in = demandIn(field(rng), rng);
    const auto out = split.step(in, 0);
    REQUIRE(out.delivered == 1.0);
    const Eigen::Vector3d& B = in.b_B_T;
    const Eigen::Vector3d& C = in.c_demand_B_Nm;
    // The flaps' torque is what the plant's flap model gives for the commanded angles.
    const Eigen::Vector2d c = sim::Flaps::normalisedTorques(out.flaps.theta_rad);
    const Eigen::Vector3d c_aero = kFlapScale_Nm * Eigen::Vector3d(c(0), 0.0, c(1));
    checkDemandMet(in, out, c_aero);
    // Any flap torque (a, 0, b) that completes C has (a, 0, b)·B = C·B; the least of them has
    // norm |C·B|/√(Bx² + Bz²), >= the component of C along B, equal when By = 0.
    const double along_B = std::abs(C.dot(B)) / B.norm();
    const double least = std::abs(C.dot(B)) / std::hypot(B.x(), B.z());
    CHECK(c_aero.norm() == Approx(least).epsilon(1e-9));
    CHECK(c_aero.norm() >= along_B * (1.0 - 1e-12));
    CHECK(c_aero.norm() <= along_B / std::cos(std::asin(std::abs(B.y()) / B.norm())) * (1.0 + 1e-9));
  }
  // Field in the roll-yaw plane (polar orbit, seed): the flaps give exactly the component along B.
  AeroAllocationInput polar;
  polar.b_B_T = {2e-5, 0.0, -3e-5};
  polar.c_demand_B_Nm = {1e-5, -2e-5, 3e-5};
  polar.flap_scale_Nm = kFlapScale_Nm;
  const auto out = split.step(polar, 0);
  const Eigen::Vector3d b_hat = polar.b_B_T.normalized();
  CHECK(out.c_aero_B_Nm.isApprox(b_hat * b_hat.dot(polar.c_demand_B_Nm), 1e-9));
}

TEST_CASE("S2 split on an equatorial orbit (claim 8): the flaps give roll and pitch, the coils the rest",
          "[unloading_controller][unit][s2]") {
  AeroAllocationParams p = wide(AeroSplit::kMagneticAero);
  p.wings = sim::FlapWings::kAlongZ;
  const AeroAllocation split(p);
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> tilt(-0.35, 0.35);
  for (int k = 0; k < 2000; ++k) {
    // The field near the equator: along the orbit normal (pitch), tilted by up to ~26°.
    const AeroAllocationInput in = demandIn(3e-5 * Eigen::Vector3d(tilt(rng), -1.0, tilt(rng)).normalized(), rng);
    const auto out = split.step(in, 0);
    REQUIRE(out.delivered == 1.0);
    const Eigen::Vector3d& B = in.b_B_T;
    const Eigen::Vector3d& C = in.c_demand_B_Nm;
    // The plant's torque for these angles with the wings along z: K (c_ax, −c_az, 0).
    const Eigen::Vector2d c = sim::Flaps::normalisedTorques(out.flaps.theta_rad);
    const Eigen::Vector3d c_aero = kFlapScale_Nm * Eigen::Vector3d(c(0), -c(1), 0.0);
    checkDemandMet(in, out, c_aero);
    // The least roll–pitch torque that completes C: (a, b, 0)·B = C·B, norm |C·B|/√(Bx² + By²).
    CHECK(c_aero.norm() == Approx(std::abs(C.dot(B)) / std::hypot(B.x(), B.y())).epsilon(1e-9));
    CHECK(out.c_aero_B_Nm.isApprox(c_aero, 1e-9));
  }
  // The field along pitch: the flaps take C's pitch, all of it; the coils roll and yaw.
  AeroAllocationInput along_pitch;
  along_pitch.b_B_T = {0.0, -3e-5, 0.0};
  along_pitch.c_demand_B_Nm = {1e-5, -2e-5, 3e-5};
  along_pitch.flap_scale_Nm = kFlapScale_Nm;
  const auto out = split.step(along_pitch, 0);
  CHECK(out.c_aero_B_Nm.isApprox(Eigen::Vector3d(0.0, -2e-5, 0.0), 1e-9));
  CHECK(out.c_magnetic_B_Nm.isApprox(Eigen::Vector3d(1e-5, 0.0, 3e-5), 1e-9));
  // Wings along y there, as on a polar orbit: B has no part in their roll–yaw plane, so no
  // flap torque can complete C; the coils give C ⟂ B and the pitch is lost.
  const auto polar_wings = AeroAllocation(wide(AeroSplit::kMagneticAero)).step(along_pitch, 0);
  CHECK(polar_wings.c_aero_B_Nm.isZero(0.0));
  CHECK(polar_wings.c_magnetic_B_Nm.isApprox(Eigen::Vector3d(1e-5, 0.0, 3e-5), 1e-9));
}

TEST_CASE("S2 split: less flap drag than the flaps alone for the same torques", "[unloading_controller][unit][s2]") {
  const AeroAllocation seed(wide(AeroSplit::kMagneticAero));
  const AeroAllocation flaps_only(wide(AeroSplit::kFlapsOnly));
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  double drag_seed = 0.0;
  double drag_flaps = 0.0;
  double torque_seed = 0.0;
  double torque_flaps = 0.0;
  constexpr int kCases = 2000;
  for (int k = 0; k < kCases; ++k) {
    AeroAllocationInput in;
    in.b_B_T = field(rng);
    in.c_demand_B_Nm = 1e-5 * Eigen::Vector3d(n(rng), n(rng), n(rng));
    in.flap_scale_Nm = kFlapScale_Nm;
    const auto a = seed.step(in, 0);
    const auto b = flaps_only.step(in, 0);
    REQUIRE(a.delivered == 1.0);
    REQUIRE(b.delivered == 1.0);
    // Flaps alone: roll and yaw from the flaps, pitch from the coils (C's y ⟂ B's x-z part).
    CHECK((b.c_aero_B_Nm - Eigen::Vector3d(in.c_demand_B_Nm.x(), 0.0, in.c_demand_B_Nm.z())).norm() <
          1e-9 * in.c_demand_B_Nm.norm());
    const double da = FlapInversion::dragShape(a.flaps.theta_rad);
    const double db = FlapInversion::dragShape(b.flaps.theta_rad);
    drag_seed += da;
    drag_flaps += db;
    torque_seed += a.c_aero_B_Nm.norm();
    torque_flaps += b.c_aero_B_Nm.norm();
  }
  // Over many demands, not each: a yaw-heavy C_A costs more drag per torque (a yaw pair's
  // lifts cancel) than a roll-heavy one, so a smaller flap torque can cost more drag.
  INFO("flap torque ratio " << torque_seed / torque_flaps << ", drag ratio " << drag_seed / drag_flaps);
  CHECK(torque_seed < 0.8 * torque_flaps);
  CHECK(drag_seed < 0.8 * drag_flaps);
}

TEST_CASE("S2 split: a coil or flap limit scales the whole demand, keeping its direction", "[unloading_controller][unit][s2]") {
  AeroAllocationParams p = wide(AeroSplit::kMagneticAero);
  p.max_dipole_Am2 = Eigen::Vector3d::Constant(0.2);
  const AeroAllocation split(p);
  AeroAllocationInput in;
  in.b_B_T = {2e-5, 5e-6, -3e-5};
  in.c_demand_B_Nm = {4e-5, -6e-5, 2e-5};
  in.flap_scale_Nm = kFlapScale_Nm;
  const auto out = split.step(in, 0);
  REQUIRE(out.coils_saturated);
  CHECK(out.delivered < 1.0);
  CHECK(out.m_B_Am2.cwiseAbs().maxCoeff() <= 0.2 + 1e-12);
  CHECK((out.c_magnetic_B_Nm + out.c_aero_B_Nm - out.delivered * in.c_demand_B_Nm).norm() <
        1e-9 * in.c_demand_B_Nm.norm());

  AeroAllocationInput thin = in;  // little air: the flaps limit it
  thin.flap_scale_Nm = 1e-7;
  const auto limited = AeroAllocation(wide(AeroSplit::kMagneticAero)).step(thin, 0);
  CHECK(limited.flaps_saturated);
  CHECK(limited.delivered < 1.0);
  CHECK((limited.c_magnetic_B_Nm + limited.c_aero_B_Nm - limited.delivered * in.c_demand_B_Nm).norm() <
        1e-9 * in.c_demand_B_Nm.norm());

  AeroAllocationInput vacuum = in;  // no air: the coils alone, C⊥B
  vacuum.flap_scale_Nm = 0.0;
  const auto coils = AeroAllocation(wide(AeroSplit::kMagneticAero)).step(vacuum, 0);
  const Eigen::Vector3d b_hat = in.b_B_T.normalized();
  CHECK(coils.c_magnetic_B_Nm.isApprox(in.c_demand_B_Nm - b_hat * b_hat.dot(in.c_demand_B_Nm), 1e-9));
  CHECK(coils.flaps.theta_rad.isZero(0.0));
}

TEST_CASE("S2 split: drag-only brakes with the flaps and leaves the torque to the coils", "[unloading_controller][unit][s2]") {
  AeroAllocationParams p = wide(AeroSplit::kDragOnly);
  p.drag_only_angle_rad = 0.5;
  const AeroAllocation split(p);
  AeroAllocationInput in;
  in.b_B_T = {2e-5, 5e-6, -3e-5};
  in.c_demand_B_Nm = {4e-6, -6e-6, 2e-6};
  in.flap_scale_Nm = kFlapScale_Nm;
  const auto out = split.step(in, 0);
  CHECK(FlapInversion::dragShape(out.flaps.theta_rad) == Approx(4.0 * std::pow(std::sin(0.5), 3)));
  CHECK(out.c_aero_B_Nm.norm() < 1e-20);
  const Eigen::Vector3d b_hat = in.b_B_T.normalized();
  CHECK(out.c_magnetic_B_Nm.isApprox(in.c_demand_B_Nm - b_hat * b_hat.dot(in.c_demand_B_Nm), 1e-9));

  p.drag_only_angle_rad = 1.2;  // beyond the flaps' 54.7°
  CHECK_THROWS_WITH(AeroAllocation(p), Catch::Contains("drag_only_angle_rad"));
}
