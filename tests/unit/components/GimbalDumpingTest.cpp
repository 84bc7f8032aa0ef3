// SPDX-License-Identifier: Apache-2.0
// Seed S3's momentum dumping by gimbal offsets: the angles whose thrust
// torque, as the plant's thruster model delivers it, is −H over what is left
// of the dump burn.
#include <cmath>

#include <catch2/catch.hpp>

#include "components/thruster_sequencer/GimbalDumping.hpp"
#include "tests/support/TestUnits.hpp"

using namespace flatsat;
using namespace flatsat::thruster_sequencer;

namespace {

/// The seed's NC(22): on the zenith face, thrust through the centre of mass,
/// gimbals ±2° east–west (axis 1) and north–south (axis 2); one y wheel.
GimbalDumpingParams northCentre() {
  sim::ThrusterParams t;
  t.direction_B = Eigen::Vector3d(0.0, -std::cos(36 * kDeg), -std::sin(36 * kDeg));
  t.r_B_m = -1.5 * t.direction_B;
  t.thrust_N = 0.165;
  t.gimballed = true;
  t.gimbal_axis1_B = Eigen::Vector3d(0.0, t.direction_B.z(), -t.direction_B.y());
  t.gimbal_axis2_B = Eigen::Vector3d::UnitX();
  t.gimbal_min_rad = Eigen::Vector2d::Constant(-2 * kDeg);
  t.gimbal_max_rad = Eigen::Vector2d::Constant(2 * kDeg);
  GimbalDumpingParams p;
  p.thrusters = {t, t};
  p.thrusters[1].gimballed = false;
  p.wheels.count = 3;
  p.wheels.inertia_kg_m2 = Eigen::Vector4d::Constant(0.2);
  p.dump_time_s = 3600.0;
  return p;
}

}  // namespace

TEST_CASE("S3 gimbal dumping: the offsets' thrust torque is -H over the burn's rest, where the gimbals reach it",
          "[thruster_sequencer][s3]") {
  const GimbalDumpingParams p = northCentre();
  const GimbalDumping dumping(p);
  const sim::Thrusters thrusters(p.thrusters);
  sim::ThrusterVector on = sim::ThrusterVector::Zero(), dumps = sim::ThrusterVector::Zero();
  on(0) = 60.0;
  dumps(0) = 3600.0;  // an hour of the dump burn left
  // A momentum the gimbals can answer: along what 0.5° on each axis gives.
  const Eigen::Vector3d reachable = thrusters.fire(on, [] {
    sim::ThrusterGimbals g = sim::ThrusterGimbals::Zero();
    g.col(0) << 0.5 * kDeg, -0.5 * kDeg;
    return g;
  }(), 60.0).torque_B_Nm;
  const Eigen::Vector4d speeds = Eigen::Vector4d(-reachable.x(), -reachable.y(), -reachable.z(), 0.0) * 3600.0 / 0.2;
  const sim::ThrusterGimbals angles = dumping.angles(on, dumps, speeds, 60.0);
  const Eigen::Vector3d torque = thrusters.fire(on, angles, 60.0).torque_B_Nm;
  CHECK((torque - reachable).norm() < 1e-3 * reachable.norm());
  CHECK(angles.col(0).isApprox(Eigen::Vector2d(0.5 * kDeg, -0.5 * kDeg), 1e-3));
  // Ten times that is past the ±2° gimbals: each angle stops at its limit.
  const sim::ThrusterGimbals clamped = dumping.angles(on, dumps, 10.0 * speeds, 60.0);
  CHECK(clamped.col(0).cwiseAbs().isApprox(Eigen::Vector2d::Constant(2 * kDeg)));
  // With ten minutes left the same momentum asks six times the torque; past
  // dump_time_s (an hour here) a longer burn asks no less.
  dumps(0) = 600.0;
  CHECK(dumping.angles(on, dumps, speeds / 6.0, 60.0).col(0).isApprox(angles.col(0), 1e-3));
  dumps(0) = 7200.0;
  CHECK(dumping.angles(on, dumps, speeds, 60.0).col(0).isApprox(angles.col(0), 1e-3));
  dumps(0) = 3600.0;
  // A thruster off, not dumping, or without gimbals keeps zero angles.
  on(1) = 60.0;
  dumps(1) = 3600.0;
  CHECK(dumping.angles(on, dumps, speeds, 60.0).col(1).isZero());
  dumps(0) = 0.0;
  CHECK(dumping.angles(on, dumps, speeds, 60.0).isZero());
}
