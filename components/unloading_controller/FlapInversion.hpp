// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace flatsat::unloading_controller {

/// Which of the seed's plate patterns gave the angles (algorithms.md S2).
enum class FlapBranch {
  kNeutral,        // c = 0: every plate edge-on
  kOnePerWing,     // rule 1a/1c: one plate per wing, both with the sign of c_ax (C2 <= 1)
  kYawPair,        // rule 1b/1d and 2: both plates of one wing, opposite signs (C2 >= 1)
  kYawPairSpread,  // 1b/1d with a plate of that wing failed: its partner + both plates of the other wing
  kDragOnly,       // θ1 = −θ3 = θ2 = −θ4: drag, no torque
  kUnavailable     // the failed plates leave no pattern for this demand
};

const char* branchName(FlapBranch branch);

struct FlapInversionParams {
  /// [rad] largest |θi| used, (0, asin √(2/3)]: beyond asin √(2/3) ≈ 54.7° a plate's roll
  /// shape sin θ cos θ |sin θ| falls while its drag |sin θ|³ still grows.
  double max_angle_rad = 0.9553166181245093;
  std::array<bool, 4> failed{};  // [-] plates θ1..θ4 stuck edge-on (neutral), replaced per the table
  /// [-] true: the seed's closed forms (IV–IX, small-angle shapes) give the angles as they
  /// are, without the Newton refinement: their torque is off by the small-angle error.
  bool seed_closed_form = false;

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct FlapSolution {
  Eigen::Vector4d theta_rad = Eigen::Vector4d::Zero();  // [rad] θ1..θ4
  Eigen::Vector2d c_achieved = Eigen::Vector2d::Zero();  // [-] (c_ax, c_az) of these angles (sim::Flaps)
  double scale = 1.0;      // [-] share of the demand delivered, direction kept: < 1 when out of reach
  FlapBranch branch = FlapBranch::kNeutral;
  bool replaced = false;   // a failed plate's job went to another plate (the replacement table)
};

/// The seed's flap inversion (CNES FR2718105 / CN1148836, eqs. IV–IX; algorithms.md S2),
/// made exact. Per plate the normalised roll and yaw shapes are
///   g(θ) = ½ sin 2θ |sin θ| = sgn θ · y √(1 − y),   h_i(θ) = (−1)^i |sin θ|³ = (−1)^i y^{3/2}
/// with y = sin²θ. The seed's closed forms solve the small-angle system (√(1 − y) → 1): they
/// are kept as the starting point, and a Newton iteration in (y_a, y_b) on the exact shapes
/// takes the residual to 1e-13, so angles → (c_ax, c_az) → angles → the same torques.
/// The branches are the seed's (C2 = c_az²/|c_ax|³): C2 <= 1 one plate on each wing with
/// the sign of c_ax (1a, 1c: the same equations with either sign of c_az); otherwise the two
/// plates of the wing whose drag gives the yaw's sign, with opposite signs (1b, 1d, and rule 2
/// as their c_ax → 0 limit, without the seed's jump at |c_ax| = 1e-4).
///
/// Replacement table (the seed's Table 1 is lost): a failed plate's job goes to its wing
/// partner, G1 ↔ G3, G2 ↔ G4; a yaw pair with one plate failed takes the partner (y_a) and
/// both plates of the other wing (y_b, opposite sign):
///   g(y_a) − 2 g(y_b) = |c_ax|,   ±(y_a^{3/2} − 2 y_b^{3/2}) = c_az;
/// drag-only: the partner and one plate of the other wing at θ and −θ.
/// Derivation: docs/magnetic_control.md, "Replacement table" (seed S2).
class FlapInversion {
 public:
  using Params = FlapInversionParams;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit FlapInversion(const Params& params);

  /// Angles for normalised torques c = (c_ax, c_az); out of reach: the largest share of c
  /// (same direction) the working plates give within max_angle_rad.
  FlapSolution solve(const Eigen::Vector2d& c) const;

  /// Drag without torque: the nominal θ1 = −θ3 = θ2 = −θ4 = θ, or the two-plate form above
  /// with a plate failed. θ is limited to max_angle_rad.
  FlapSolution dragOnly(double theta_rad) const;

  /// [-] Σ |sin θi|³: the flaps' drag in units of 4ρ(S/2)V² (seed: drag coefficient 4|sin³θ|).
  static double dragShape(const Eigen::Vector4d& theta_rad);

  const Params& params() const { return params_; }

 private:
  struct Pattern;
  Pattern onePerWing() const;
  Pattern yawPair(bool yaw_positive) const;
  bool solveExact(const Pattern& pattern, const Eigen::Vector2d& c, FlapSolution& out) const;
  FlapSolution solveReachable(const Eigen::Vector2d& c) const;

  Params params_;
  double y_max_;  // sin² of max_angle_rad
};

/// The seed's small-angle closed forms (eqs. IV–VII), S_a² and S_b² with S = |sin θ|/|c_ax|^½,
/// for the first and second plate of the branch (1a: θ1, θ2; 1b: θ2, θ4). C2 = c_az²/|c_ax|³.
/// They solve S_a² + S_b² = 1, S_b³ − S_a³ = √C2 (C2 <= 1) and S_a² − S_b² = 1,
/// S_a³ + S_b³ = √C2 (C2 >= 1); exposed so the transcription can be checked.
Eigen::Vector2d seedSmallAngleSquares(double C2, bool yaw_negative);

}  // namespace flatsat::unloading_controller
