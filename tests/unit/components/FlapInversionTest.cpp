// SPDX-License-Identifier: Apache-2.0
// Seed S2's flap inversion (algorithms.md S2): every branch round-trips through the plant's
// own forward model (sim::Flaps::normalisedTorques), failed plates are replaced per the
// derived table, and drag-only gives no torque.
#include <cmath>

#include <catch2/catch.hpp>

#include "components/unloading_controller/FlapInversion.hpp"
#include "sim/Flaps.hpp"
#include "tests/support/TestUnits.hpp"

using flatsat::sim::Flaps;
using flatsat::unloading_controller::FlapBranch;
using flatsat::unloading_controller::FlapInversion;
using flatsat::unloading_controller::FlapInversionParams;
using flatsat::unloading_controller::FlapSolution;
using flatsat::unloading_controller::seedSmallAngleSquares;

namespace {

constexpr double kRoundTrip = 1e-9;

/// Angles of a two-unknown pattern: plates a and b at ±asin √y, as the seed's branches set them.
Eigen::Vector4d pattern(int a, double ya, double sign_a, int b, double yb, double sign_b) {
  Eigen::Vector4d theta = Eigen::Vector4d::Zero();
  theta(a) = sign_a * std::asin(std::sqrt(ya));
  theta(b) = sign_b * std::asin(std::sqrt(yb));
  return theta;
}

struct Trip {
  int cases = 0;
  int worse = 0;
  double worst = 0.0;
};

/// c of the angles (plant model) → solve → c of the solution (plant model): same torques.
void roundTrip(const FlapInversion& inversion, const Eigen::Vector4d& theta, Trip& trip) {
  const Eigen::Vector2d c = Flaps::normalisedTorques(theta);
  const FlapSolution s = inversion.solve(c);
  const double error = (Flaps::normalisedTorques(s.theta_rad) - c).lpNorm<Eigen::Infinity>();
  ++trip.cases;
  trip.worst = std::max(trip.worst, error);
  const auto& p = inversion.params();
  const bool ok = error <= kRoundTrip && s.scale == 1.0 &&
                  s.theta_rad.cwiseAbs().maxCoeff() <= p.max_angle_rad + 1e-12;
  bool failed_edge_on = true;
  for (int i = 0; i < 4; ++i) failed_edge_on = failed_edge_on && (!p.failed[i] || s.theta_rad(i) == 0.0);
  if (!ok || !failed_edge_on) {
    if (trip.worse++ < 5) {
      UNSCOPED_INFO("theta_deg " << (theta / kDeg).transpose() << " c " << c.transpose() << " -> "
                                 << (s.theta_rad / kDeg).transpose() << " scale " << s.scale << " branch "
                                 << branchName(s.branch) << " error " << error);
    }
  }
}

/// Dense grid over the seed's patterns, both signs of c_ax, y = sin²θ from 1e-6 to
/// sin²(50°). Nominal: 1a/1c (θ1, θ2 with sgn c_ax), 1b (θ2, −θ4), 1d (θ1, −θ3) and their
/// c_ax → 0 limit (rule 2). With plate `dead` failed, the table's patterns: one plate per wing
/// with the partner, the intact wing's yaw pair, and the spread yaw (partner + the other wing).
Trip gridOverBranches(const FlapInversion& inversion, int dead = -1) {
  Trip trip;
  constexpr int kSteps = 60;
  const double y_max = std::pow(std::sin(50.0 * kDeg), 2);
  auto shape = [](double y) { return y * std::sqrt(1.0 - y); };
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; j <= kSteps; ++j) {
      const double ya = 1e-6 + (y_max - 1e-6) * std::pow(static_cast<double>(i) / kSteps, 2);
      const double yb = 1e-6 + (y_max - 1e-6) * std::pow(static_cast<double>(j) / kSteps, 2);
      for (const double s : {1.0, -1.0}) {
        if (dead < 0) {
          roundTrip(inversion, pattern(0, ya, s, 1, yb, s), trip);
          roundTrip(inversion, pattern(1, ya, s, 3, yb, -s), trip);
          roundTrip(inversion, pattern(0, ya, s, 2, yb, -s), trip);
          continue;
        }
        const int m = dead == 0 ? 2 : 0;
        const int q = dead == 1 ? 3 : 1;
        roundTrip(inversion, pattern(m, ya, s, q, yb, s), trip);
        const int o1 = (dead + 1) % 4;
        roundTrip(inversion, pattern(o1, ya, s, (o1 + 2) % 4, yb, -s), trip);
        if (shape(ya) >= 2.0 * shape(yb)) {  // the spread pattern's own range: c_ax has the lead's sign
          Eigen::Vector4d theta = pattern((dead + 2) % 4, ya, s, o1, yb, -s);
          theta((o1 + 2) % 4) = theta(o1);
          roundTrip(inversion, theta, trip);
        }
      }
    }
  }
  return trip;
}

}  // namespace

TEST_CASE("S2 flaps: the seed's closed forms solve its small-angle equations (transcription check)",
          "[unloading_controller][unit][s2]") {
  // Eq. IV: S1² + S2² = 1 and S2³ − S1³ = √C2 for C2 in [0, 1] (1c: the same, swapped).
  for (double C2 = 0.0; C2 <= 1.0; C2 += 0.01) {
    const Eigen::Vector2d s = seedSmallAngleSquares(C2, false);
    CHECK(s.sum() == Approx(1.0).margin(1e-12));
    CHECK(std::pow(s(1), 1.5) - std::pow(s(0), 1.5) == Approx(std::sqrt(C2)).margin(1e-9));
    const Eigen::Vector2d swapped = seedSmallAngleSquares(C2, true);
    CHECK(swapped(0) == s(1));
  }
  // Eqs. V, VII: S_a² − S_b² = 1 and S_a³ + S_b³ = √C2 for C2 >= 1.
  for (double C2 = 1.2; C2 <= 1e4; C2 *= 1.2) {  // at C2 = 1 both forms meet: (0, 1) and (1, 0)
    const Eigen::Vector2d s = seedSmallAngleSquares(C2, false);
    CHECK(s(0) - s(1) == Approx(1.0).margin(1e-9));
    CHECK(std::pow(s(0), 1.5) + std::pow(s(1), 1.5) == Approx(std::sqrt(C2)).epsilon(1e-9));
  }
}

TEST_CASE("S2 flaps: angles -> c_ax, c_az -> angles gives the same torques to 1e-9 in every branch",
          "[unloading_controller][unit][s2]") {
  const FlapInversion inversion(FlapInversionParams{});
  const Trip trip = gridOverBranches(inversion);
  INFO("cases " << trip.cases << ", worst |c - c'| " << trip.worst);
  CHECK(trip.cases == 61 * 61 * 6);
  CHECK(trip.worse == 0);

  // The seed's limits: pure yaw of either sign (rule 2) and pure roll (C2 = 0).
  for (const Eigen::Vector2d& c : {Eigen::Vector2d(0.0, 0.3), Eigen::Vector2d(0.0, -0.3), Eigen::Vector2d(0.4, 0.0),
                                  Eigen::Vector2d(-0.4, 0.0), Eigen::Vector2d(1e-5, 0.2)}) {
    const FlapSolution s = inversion.solve(c);
    INFO("c " << c.transpose() << " branch " << branchName(s.branch));
    CHECK((Flaps::normalisedTorques(s.theta_rad) - c).lpNorm<Eigen::Infinity>() < 1e-12);
  }
  // Pure yaw uses the two plates of one wing at opposite angles (the seed's θ2 = −θ4).
  const FlapSolution yaw = inversion.solve({0.0, 0.3});
  CHECK(yaw.branch == FlapBranch::kYawPair);
  CHECK(yaw.theta_rad(1) == Approx(-yaw.theta_rad(3)).margin(1e-12));
  CHECK(yaw.theta_rad(0) == 0.0);
  CHECK(yaw.theta_rad(2) == 0.0);
  CHECK(inversion.solve(Eigen::Vector2d::Zero()).theta_rad.isZero(0.0));
}

TEST_CASE("S2 flaps: a single failed plate is replaced per the symmetry table in every branch",
          "[unloading_controller][unit][s2]") {
  for (int dead = 0; dead < 4; ++dead) {
    FlapInversionParams p;
    p.failed[dead] = true;
    const FlapInversion inversion(p);
    const Trip trip = gridOverBranches(inversion, dead);
    INFO("plate " << dead + 1 << " failed: cases " << trip.cases << ", worst |c - c'| " << trip.worst);
    CHECK(trip.worse == 0);
  }
  // One plate per wing (C2 <= 1): the failed plate's wing partner takes its angle, at the same drag.
  const FlapInversion nominal(FlapInversionParams{});
  FlapInversionParams p1;
  p1.failed[0] = true;
  const FlapInversion without_1(p1);
  const Eigen::Vector2d c(0.2, 0.03);
  const FlapSolution a = nominal.solve(c);
  const FlapSolution b = without_1.solve(c);
  REQUIRE(a.branch == FlapBranch::kOnePerWing);
  REQUIRE(b.branch == FlapBranch::kOnePerWing);
  CHECK_FALSE(a.replaced);
  CHECK(b.replaced);
  CHECK(b.theta_rad(0) == 0.0);
  CHECK(b.theta_rad(2) == Approx(a.theta_rad(0)).margin(1e-12));  // G1 -> G3
  CHECK(b.theta_rad(1) == Approx(a.theta_rad(1)).margin(1e-12));
  CHECK(FlapInversion::dragShape(b.theta_rad) == Approx(FlapInversion::dragShape(a.theta_rad)).margin(1e-15));

  // Yaw pair with one of its plates failed: its partner and both plates of the other wing,
  // which costs drag.
  FlapInversionParams p4;
  p4.failed[3] = true;
  const FlapInversion without_4(p4);
  const FlapSolution yaw = without_4.solve({0.01, 0.3});
  CHECK(yaw.branch == FlapBranch::kYawPairSpread);
  CHECK(yaw.replaced);
  CHECK(yaw.theta_rad(3) == 0.0);
  CHECK(yaw.theta_rad(0) == Approx(yaw.theta_rad(2)).margin(1e-12));
  CHECK(FlapInversion::dragShape(yaw.theta_rad) > FlapInversion::dragShape(nominal.solve({0.01, 0.3}).theta_rad));
}

TEST_CASE("S2 flaps: drag-only angles give drag and no torque, also with a failed plate", "[unloading_controller][unit][s2]") {
  const double theta = 30.0 * kDeg;
  const double u3 = std::pow(std::sin(theta), 3);
  const FlapSolution nominal = FlapInversion(FlapInversionParams{}).dragOnly(theta);
  CHECK(nominal.theta_rad(0) == theta);
  CHECK(nominal.theta_rad(2) == -theta);  // θ1 = −θ3 = θ2 = −θ4
  CHECK(Flaps::normalisedTorques(nominal.theta_rad).lpNorm<Eigen::Infinity>() < 1e-15);
  CHECK(FlapInversion::dragShape(nominal.theta_rad) == Approx(4.0 * u3));
  for (int dead = 0; dead < 4; ++dead) {
    FlapInversionParams p;
    p.failed[dead] = true;
    const FlapSolution s = FlapInversion(p).dragOnly(theta);
    INFO("plate " << dead + 1 << " failed: " << (s.theta_rad / kDeg).transpose());
    CHECK(s.branch == FlapBranch::kDragOnly);
    CHECK(s.theta_rad(dead) == 0.0);
    CHECK(Flaps::normalisedTorques(s.theta_rad).lpNorm<Eigen::Infinity>() < 1e-15);
    CHECK(FlapInversion::dragShape(s.theta_rad) == Approx(2.0 * u3));
  }
}

TEST_CASE("S2 flaps: a demand out of reach is scaled down along its direction to the angle limit",
          "[unloading_controller][unit][s2]") {
  FlapInversionParams p;
  p.max_angle_rad = 20.0 * kDeg;
  const FlapInversion inversion(p);
  const Eigen::Vector2d c(0.5, -0.2);
  const FlapSolution s = inversion.solve(c);
  REQUIRE(s.scale > 0.0);
  CHECK(s.scale < 1.0);
  CHECK((Flaps::normalisedTorques(s.theta_rad) - s.scale * c).lpNorm<Eigen::Infinity>() < 1e-9);
  CHECK(s.theta_rad.cwiseAbs().maxCoeff() == Approx(p.max_angle_rad).epsilon(1e-6));  // at the limit
  CHECK(inversion.solve((s.scale + 1e-6) * c).scale < 1.0);

  FlapInversionParams bad;
  bad.max_angle_rad = 60.0 * kDeg;
  CHECK_THROWS_WITH(FlapInversion(bad), Catch::Contains("max_angle_rad"));
}

TEST_CASE("S2 flaps: the seed's closed forms as the solver, off by the small-angle error only",
          "[unloading_controller][unit][s2]") {
  FlapInversionParams exact_params;
  FlapInversionParams seed_params;
  seed_params.seed_closed_form = true;
  const FlapInversion exact(exact_params);
  const FlapInversion seed(seed_params);
  for (const Eigen::Vector2d& c : {Eigen::Vector2d(0.02, 0.004), Eigen::Vector2d(-0.01, 0.03), Eigen::Vector2d(0.05, -0.01)}) {
    const FlapSolution e = exact.solve(c);
    const FlapSolution s = seed.solve(c);
    REQUIRE(e.branch != FlapBranch::kUnavailable);
    REQUIRE(s.branch == e.branch);
    CHECK((e.c_achieved - c).norm() < 1e-12);
    // The seed's shapes drop √(1 − y), y = sin²θ: the torque it gets is short by about y/2.
    const double y = std::pow(std::sin(s.theta_rad.cwiseAbs().maxCoeff()), 2);
    const double error = (s.c_achieved - c).norm() / c.norm();
    INFO("c " << c.transpose() << ": closed form off by " << error << ", y " << y);
    CHECK(error > 0.0);
    CHECK(error < y);
    // A demand ten times smaller: smaller angles, smaller error.
    const FlapSolution small = seed.solve(0.1 * c);
    CHECK((small.c_achieved - 0.1 * c).norm() / (0.1 * c.norm()) < error);
  }
}
