// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/FlapInversion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "components/common/Validation.hpp"
#include "sim/Flaps.hpp"

namespace flatsat::unloading_controller {
namespace {

constexpr double kMaxUsefulAngle_rad = 0.9553166181245093;  // asin √(2/3)
constexpr double kTolerance = 1e-13;                          // [-] on (c_ax, c_az)

// (−1)^i of the seed's 1-based plate number: plates 1, 3 (+y wing) yaw −, 2, 4 (−y wing) yaw +
// (sim::Flaps::normalisedTorques' sign; the Newton residual below needs it per plate).
constexpr double yawSign(int plate) { return plate % 2 == 0 ? -1.0 : 1.0; }
// Wing partner: same wing, same centroid (G1 ↔ G3, G2 ↔ G4).
constexpr int partner(int plate) { return (plate + 2) % 4; }

double rollShape(double y) { return y * std::sqrt(1.0 - y); }                 // g / sgn θ
double rollSlope(double y) { return std::sqrt(1.0 - y) - y / (2.0 * std::sqrt(1.0 - y)); }

}  // namespace

/// One seed pattern: plate i takes unknown var[i] (0 or 1; −1: edge-on) with the sign
/// sign[i] × sgn(c_ax).
struct FlapInversion::Pattern {
  FlapBranch branch = FlapBranch::kUnavailable;
  std::array<int, 4> var{-1, -1, -1, -1};
  std::array<double, 4> sign{};
  bool replaced = false;

  Eigen::Vector4d angles(const Eigen::Vector2d& y, double roll_sign) const {
    Eigen::Vector4d theta = Eigen::Vector4d::Zero();
    for (int i = 0; i < 4; ++i) {
      if (var[i] >= 0) theta(i) = sign[i] * roll_sign * std::asin(std::sqrt(y(var[i])));
    }
    return theta;
  }
};

const char* branchName(FlapBranch branch) {
  switch (branch) {
    case FlapBranch::kNeutral: return "neutral";
    case FlapBranch::kOnePerWing: return "one_per_wing";
    case FlapBranch::kYawPair: return "yaw_pair";
    case FlapBranch::kYawPairSpread: return "yaw_pair_spread";
    case FlapBranch::kDragOnly: return "drag_only";
    case FlapBranch::kUnavailable: return "unavailable";
  }
  return "?";
}

std::vector<std::string> FlapInversionParams::validate() const {
  std::vector<std::string> errors;
  if (!(max_angle_rad > 0.0 && max_angle_rad <= kMaxUsefulAngle_rad)) {
    errors.push_back("max_angle_rad: must be in (0, asin(sqrt(2/3)) = 54.7 deg]");
  }
  if (std::all_of(failed.begin(), failed.end(), [](bool f) { return f; })) {
    errors.push_back("failed: all four plates failed");
  }
  return errors;
}

Eigen::Vector2d seedSmallAngleSquares(double C2, bool c_az_negative) {
  if (C2 <= 1.0) {
    // Eq. IV: X = −½ + cos(arccos(1 − 2 C2)/3); S1², S2² = ½ ∓ ½ √(1 − 4X²) (1a; 1c swaps them).
    const double X = -0.5 + std::cos(std::acos(1.0 - 2.0 * C2) / 3.0);
    const double root = std::sqrt(std::max(0.0, 1.0 - 4.0 * X * X));
    const Eigen::Vector2d s(0.5 - 0.5 * root, 0.5 + 0.5 * root);
    return c_az_negative ? Eigen::Vector2d(s(1), s(0)) : s;
  }
  // Eqs. V, VII: a = ½[C2 + √(C2² − 1)]^⅓ + ½[C2 − √(C2² − 1)]^⅓,
  // s = a^½ [1 + (C2^½/a^{3/2} − 1)^½], S_a = (s + 1/s)/2, S_b = (s − 1/s)/2.
  const double r = std::sqrt(C2 * C2 - 1.0);
  const double a = 0.5 * std::cbrt(C2 + r) + 0.5 * std::cbrt(C2 - r);
  const double s = std::sqrt(a) * (1.0 + std::sqrt(std::max(0.0, std::sqrt(C2) / std::pow(a, 1.5) - 1.0)));
  const double Sa = 0.5 * (s + 1.0 / s);
  const double Sb = 0.5 * (s - 1.0 / s);
  return {Sa * Sa, Sb * Sb};
}

FlapInversion::FlapInversion(const Params& params) : params_(validated(params, "FlapInversionParams")) {
  const double s = std::sin(params_.max_angle_rad);
  y_max_ = s * s;
}

double FlapInversion::dragShape(const Eigen::Vector4d& theta_rad) {
  double d = 0.0;
  for (int i = 0; i < 4; ++i) d += std::pow(std::abs(std::sin(theta_rad(i))), 3);
  return d;
}

bool FlapInversion::solveExact(const Pattern& p, const Eigen::Vector2d& c, FlapSolution& out) const {
  const double roll_sign = c(0) < 0.0 ? -1.0 : 1.0;
  const double cax = std::abs(c(0));
  // Start: the seed's closed form for the nominal pair; the spread pattern starts from the
  // same squares with the second plate's share split over two plates.
  Eigen::Vector2d y;
  const bool yaw_pattern = p.branch != FlapBranch::kOnePerWing;
  if (cax < 1e-12 * std::max(1.0, std::abs(c(1)))) {
    y = Eigen::Vector2d::Constant(std::pow(std::abs(c(1)) / 2.0, 2.0 / 3.0));  // rule 2 (VIII, IX)
  } else {
    const double C2 = c(1) * c(1) / (cax * cax * cax);
    y = cax * seedSmallAngleSquares(yaw_pattern ? std::max(C2, 1.0) : std::min(C2, 1.0), c(1) < 0.0);
  }
  if (p.branch == FlapBranch::kYawPairSpread) y(1) *= 0.5;
  if (params_.seed_closed_form) {
    // The seed's angles as they are; beyond the angle limit the demand is out of reach
    // (solve() then scales it down).
    if (!(y.maxCoeff() <= y_max_) || !y.allFinite()) return false;
    out.theta_rad = p.angles(y, roll_sign);
    out.c_achieved = sim::Flaps::normalisedTorques(out.theta_rad);
    out.branch = p.branch;
    out.replaced = p.replaced;
    return true;
  }
  y = y.cwiseMin(y_max_);

  // Residual and Jacobian in y: every plate adds sign·g to c_ax and (−1)^i y^{3/2} to c_az.
  auto residual = [&](const Eigen::Vector2d& v, Eigen::Matrix2d* J) {
    Eigen::Vector2d r = -c;
    if (J) J->setZero();
    for (int i = 0; i < 4; ++i) {
      if (p.var[i] < 0) continue;
      const int k = p.var[i];
      const double sg = p.sign[i] * roll_sign;
      r(0) += sg * rollShape(v(k));
      r(1) += yawSign(i) * std::pow(v(k), 1.5);
      if (J) {
        (*J)(0, k) += sg * rollSlope(v(k));
        (*J)(1, k) += yawSign(i) * 1.5 * std::sqrt(v(k));
      }
    }
    return r;
  };
  Eigen::Matrix2d J;
  Eigen::Vector2d r = residual(y, &J);
  for (int iteration = 0; iteration < 60 && r.lpNorm<Eigen::Infinity>() > kTolerance; ++iteration) {
    // The Jacobian is singular only with both unknowns at 0 (c = 0, handled before).
    const Eigen::Vector2d step = J.fullPivLu().solve(-r);
    // Damped: halve until the residual falls, staying in [0, y_max] (no wrap through 0).
    double lambda = 1.0;
    Eigen::Vector2d next;
    Eigen::Vector2d r_next;
    for (int halving = 0; halving < 40; ++halving, lambda *= 0.5) {
      next = (y + lambda * step).cwiseMax(0.0).cwiseMin(y_max_);
      r_next = residual(next, nullptr);
      if (r_next.norm() < r.norm()) break;
    }
    if (!(r_next.norm() < r.norm())) break;
    y = next;
    r = residual(y, &J);
  }
  if (r.lpNorm<Eigen::Infinity>() > 1e-12) return false;
  out.theta_rad = p.angles(y, roll_sign);
  out.c_achieved = sim::Flaps::normalisedTorques(out.theta_rad);
  out.branch = p.branch;
  out.replaced = p.replaced;
  return true;
}

FlapInversion::Pattern FlapInversion::onePerWing() const {
  // Plate 1 (or 3) and plate 2 (or 4), both with the sign of c_ax.
  const auto& failed = params_.failed;
  Pattern p;
  const int m = failed[0] ? 2 : 0;
  const int q = failed[1] ? 3 : 1;
  if (failed[m] || failed[q]) return p;
  p.branch = FlapBranch::kOnePerWing;
  p.var[m] = 0;
  p.var[q] = 1;
  p.sign[m] = p.sign[q] = 1.0;
  p.replaced = m != 0 || q != 1;
  return p;
}

FlapInversion::Pattern FlapInversion::yawPair(bool yaw_positive) const {
  // The wing whose one-sided drag has the yaw's sign: plates 2, 4 (c_az >= 0) or 1, 3.
  const auto& failed = params_.failed;
  Pattern p;
  const int a = yaw_positive ? 1 : 0;
  const int b = partner(a);
  if (!failed[a] && !failed[b]) {
    p.branch = FlapBranch::kYawPair;
    p.var[a] = 0;
    p.var[b] = 1;
    p.sign[a] = 1.0;
    p.sign[b] = -1.0;
    return p;
  }
  const int lead = failed[a] ? b : a;
  const int o1 = (a + 1) % 4;
  const int o2 = partner(o1);
  if (failed[lead] || failed[o1] || failed[o2]) return p;
  p.branch = FlapBranch::kYawPairSpread;
  p.replaced = true;
  p.var[lead] = 0;
  p.sign[lead] = 1.0;
  p.var[o1] = p.var[o2] = 1;
  p.sign[o1] = p.sign[o2] = -1.0;
  return p;
}

FlapSolution FlapInversion::solveReachable(const Eigen::Vector2d& c) const {
  FlapSolution out;
  out.branch = FlapBranch::kUnavailable;
  // The seed's test C2 <= 1 is exact for its small-angle shapes; on the exact ones the
  // border moves slightly, so the other pattern is tried when the first has no solution.
  const double cax = std::abs(c(0));
  const bool one_per_wing_first = cax > 0.0 && c(1) * c(1) <= cax * cax * cax;
  const Pattern first = one_per_wing_first ? onePerWing() : yawPair(c(1) >= 0.0);
  const Pattern second = one_per_wing_first ? yawPair(c(1) >= 0.0) : onePerWing();
  for (const Pattern* p : {&first, &second}) {
    if (p->branch != FlapBranch::kUnavailable && solveExact(*p, c, out)) return out;
    // The seed's closed forms hold for the pattern its test C2 picks only.
    if (params_.seed_closed_form) break;
  }
  return out;  // solveExact writes only what it solved
}

FlapSolution FlapInversion::solve(const Eigen::Vector2d& c) const {
  FlapSolution none;
  if (!c.allFinite() || c.isZero(0.0)) return none;
  if (FlapSolution full = solveReachable(c); full.branch != FlapBranch::kUnavailable) return full;
  // Out of reach: bisect on the share s of c (the reachable set is star-shaped about 0
  // along each pattern: smaller demands need smaller angles).
  double lo = 0.0;
  double hi = 1.0;
  FlapSolution best;
  best.scale = 0.0;
  best.branch = FlapBranch::kUnavailable;
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (lo + hi);
    FlapSolution trial = solveReachable(mid * c);
    if (trial.branch != FlapBranch::kUnavailable) {
      lo = mid;
      trial.scale = mid;
      best = trial;
    } else {
      hi = mid;
    }
  }
  return best;
}

FlapSolution FlapInversion::dragOnly(double theta_rad) const {
  FlapSolution out;
  if (!std::isfinite(theta_rad) || theta_rad == 0.0) return out;
  const double t = std::clamp(theta_rad, -params_.max_angle_rad, params_.max_angle_rad);
  const auto& failed = params_.failed;
  const int dead = static_cast<int>(std::find(failed.begin(), failed.end(), true) - failed.begin());
  if (dead == 4) {
    out.theta_rad << t, t, -t, -t;  // θ1 = −θ3 = θ2 = −θ4 (seed): lift cancels within each wing
  } else {
    // The partner of the failed plate and one plate of the other wing, at θ and −θ: lift the
    // same way on both wings (no roll), drag equal on both (no yaw).
    const int lead = partner(dead);
    const int other = failed[(dead + 1) % 4] ? (dead + 3) % 4 : (dead + 1) % 4;
    if (failed[lead] || failed[other]) {
      out.branch = FlapBranch::kUnavailable;
      return out;
    }
    out.theta_rad(lead) = t;
    out.theta_rad(other) = -t;
    out.replaced = true;
  }
  out.c_achieved = sim::Flaps::normalisedTorques(out.theta_rad);
  out.branch = FlapBranch::kDragOnly;
  return out;
}

}  // namespace flatsat::unloading_controller
