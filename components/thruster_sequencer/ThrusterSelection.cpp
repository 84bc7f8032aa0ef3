// SPDX-License-Identifier: Apache-2.0
#include "components/thruster_sequencer/ThrusterSelection.hpp"

#include <algorithm>

#include <Eigen/Dense>

namespace flatsat::thruster_sequencer {

namespace {

using Matrix6X = Eigen::Matrix<double, 6, Eigen::Dynamic>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

// Relative to the largest column norm: below it a gradient entry or a solution entry is zero.
constexpr double kTolerance = 1e-10;

/// Least squares on the columns in `passive` only; the others are zero.
Eigen::VectorXd solveOn(const Matrix6X& a, const Vector6& b, const std::vector<bool>& passive) {
  std::vector<Eigen::Index> columns;
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    if (passive[static_cast<std::size_t>(j)]) columns.push_back(j);
  }
  Matrix6X sub(6, static_cast<Eigen::Index>(columns.size()));
  for (std::size_t k = 0; k < columns.size(); ++k) sub.col(static_cast<Eigen::Index>(k)) = a.col(columns[k]);
  const Eigen::VectorXd z = sub.completeOrthogonalDecomposition().solve(b);
  Eigen::VectorXd s = Eigen::VectorXd::Zero(a.cols());
  for (std::size_t k = 0; k < columns.size(); ++k) s(columns[k]) = z(static_cast<Eigen::Index>(k));
  return s;
}

/// Lawson & Hanson (1974) NNLS, ch. 23: grow the passive set by the largest gradient entry,
/// step back toward feasibility whenever an unconstrained solution goes negative.
Eigen::VectorXd nnls(const Matrix6X& a, const Vector6& b) {
  const Eigen::Index n = a.cols();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<bool> passive(static_cast<std::size_t>(n), false);
  const double scale = std::max(a.colwise().norm().maxCoeff(), 1.0);
  const double tol = kTolerance * scale;
  for (Eigen::Index outer = 0; outer < 3 * n + 3; ++outer) {
    const Eigen::VectorXd w = a.transpose() * (b - a * x);
    Eigen::Index best = -1;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!passive[static_cast<std::size_t>(j)] && w(j) > tol && (best < 0 || w(j) > w(best))) best = j;
    }
    if (best < 0) break;
    passive[static_cast<std::size_t>(best)] = true;
    for (Eigen::Index inner = 0; inner <= n; ++inner) {
      const Eigen::VectorXd s = solveOn(a, b, passive);
      double alpha = 1.0;
      bool feasible = true;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (passive[static_cast<std::size_t>(j)] && s(j) <= tol) {
          feasible = false;
          alpha = std::min(alpha, x(j) / (x(j) - s(j)));
        }
      }
      if (feasible) {
        x = s;
        break;
      }
      x += alpha * (s - x);
      for (Eigen::Index j = 0; j < n; ++j) {
        if (passive[static_cast<std::size_t>(j)] && x(j) <= tol) {
          passive[static_cast<std::size_t>(j)] = false;
          x(j) = 0.0;
        }
      }
    }
  }
  return x;
}

}  // namespace

ThrusterFiring selectThrusters(const std::vector<sim::ThrusterParams>& thrusters,
                               const Eigen::Vector3d& torque_direction_B, double force_weight_m) {
  ThrusterFiring firing;
  const int count = std::min(static_cast<int>(thrusters.size()), sim::kMaxThrusters);
  Matrix6X a = Matrix6X::Zero(6, count);
  for (int i = 0; i < count; ++i) {
    const sim::ThrusterParams& t = thrusters[static_cast<std::size_t>(i)];
    if (t.failed) continue;
    const Eigen::Vector3d force = t.thrust_N * t.direction_B;
    a.col(i).head<3>() = t.r_B_m.cross(force);
    a.col(i).tail<3>() = force / force_weight_m;
  }
  Vector6 b = Vector6::Zero();
  b.head<3>() = torque_direction_B.normalized();
  const Eigen::VectorXd x = nnls(a, b);
  if (count == 0 || !(x.maxCoeff() > 0.0)) return firing;
  const Eigen::VectorXd weight = x / x.maxCoeff();
  firing.weight.head(count) = weight;
  firing.torque_B_Nm = a.topRows<3>() * weight;
  firing.force_B_N = a.bottomRows<3>() * weight * force_weight_m;
  // A firing that turns the body against the demand is no selection at all.
  if (!(firing.torque_B_Nm.dot(torque_direction_B) > 0.0)) return ThrusterFiring{};
  return firing;
}

}  // namespace flatsat::thruster_sequencer
