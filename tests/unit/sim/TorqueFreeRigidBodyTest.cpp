// SPDX-License-Identifier: Apache-2.0
// Torque-free asymmetric rigid body against the analytic solution of Euler's
// equations (Landau & Lifshitz, Mechanics, §37; Markley & Crassidis,
// Fundamentals of Spacecraft Attitude Determination and Control, §3.3.5).
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "sim/Attitude.hpp"
#include "sim/RigidBodyWheels.hpp"

using namespace flatsat::sim;

namespace {

struct Jacobi {
  double sn, cn, dn;
};

// sn, cn, dn (u | m) by the arithmetic-geometric mean and descending Landen
// transformation (Abramowitz & Stegun 16.4.3): a_0 = 1, b_0 = √(1 − m),
// c_0 = √m; φ_N = 2^N a_N u; φ_{n−1} = ½[φ_n + asin(c_n sin φ_n / a_n)];
// sn = sin φ_0, cn = cos φ_0. A&S's dn = cos φ_0 / cos(φ_1 − φ_0) is 0/0 at
// sn = ±1; dn = √(1 − m sn²) (16.9.1) is well conditioned for m away from 1.
Jacobi jacobi(double u, double m) {
  constexpr int kMaxTerms = 16;
  double a[kMaxTerms + 1];
  double c[kMaxTerms + 1];
  a[0] = 1.0;
  c[0] = std::sqrt(m);
  double b = std::sqrt(1.0 - m);
  int n = 0;
  while (std::abs(c[n]) > 1e-17 && n < kMaxTerms) {
    a[n + 1] = 0.5 * (a[n] + b);
    c[n + 1] = 0.5 * (a[n] - b);
    b = std::sqrt(a[n] * b);
    ++n;
  }
  double phi = std::ldexp(a[n] * u, n);
  for (int j = n; j > 0; --j) phi = 0.5 * (phi + std::asin(c[j] * std::sin(phi) / a[j]));
  const double sn = std::sin(phi);
  return {sn, std::cos(phi), std::sqrt(1.0 - m * sn * sn)};
}

Eigen::Matrix3d rotX(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix(); }
Eigen::Matrix3d rotZ(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

// Principal moments J1 < J2 < J3 and a motion with H² > 2T J2 (about axis 3):
//   ω1 = A1 cn(λt + u0), ω2 = A2 sn(λt + u0), ω3 = A3 dn(λt + u0),
//   A1² = (2TJ3 − H²) / (J1(J3 − J1)), A2² = (2TJ3 − H²) / (J2(J3 − J2)),
//   A3² = (H² − 2TJ1) / (J3(J3 − J1)), λ² = (J3 − J2)(H² − 2TJ1) / (J1J2J3),
//   m = k² = (J2 − J1)(2TJ3 − H²) / ((J3 − J2)(H² − 2TJ1))   (L&L Eq. 37.10).
struct EulerSolution {
  Eigen::Vector3d J;
  double H, A1, A2, A3, lambda, m, u0;

  EulerSolution(const Eigen::Vector3d& moments, const Eigen::Vector3d& w0) : J(moments) {
    H = J.cwiseProduct(w0).norm();
    const double two_T = w0.dot(J.cwiseProduct(w0));
    const double H2 = H * H;
    A1 = std::sqrt((two_T * J(2) - H2) / (J(0) * (J(2) - J(0))));
    A2 = std::sqrt((two_T * J(2) - H2) / (J(1) * (J(2) - J(1))));
    A3 = std::sqrt((H2 - two_T * J(0)) / (J(2) * (J(2) - J(0))));
    lambda = std::sqrt((J(2) - J(1)) * (H2 - two_T * J(0)) / (J(0) * J(1) * J(2)));
    m = (J(1) - J(0)) * (two_T * J(2) - H2) / ((J(2) - J(1)) * (H2 - two_T * J(0)));
    // u0 = F(am u0 | m), am u0 = atan2(sn, cn); |am u0| < π/2 since ω1(0) > 0.
    u0 = std::ellint_1(std::sqrt(m), std::atan2(w0(1) / A2, w0(0) / A1));
  }

  Eigen::Vector3d w(double t) const {
    const Jacobi f = jacobi(lambda * t + u0, m);
    return {A1 * f.cn, A2 * f.sn, A3 * f.dn};
  }

  // Euler angles z-x-z from an inertial frame with z along H (L&L Eq. 37.13):
  // H_P = H (sin θ sin φ, sin θ cos φ, cos θ), and the precession rate
  // α̇ = H (J1ω1² + J2ω2²) / (J1²ω1² + J2²ω2²) (L&L Eq. 37.15).
  double nutation(const Eigen::Vector3d& w) const { return std::acos(J(2) * w(2) / H); }
  double spin(const Eigen::Vector3d& w) const { return std::atan2(J(0) * w(0), J(1) * w(1)); }
  double precessionRate(double t) const {
    const Eigen::Vector3d w_t = w(t);
    const Eigen::Vector3d Jw = J.cwiseProduct(w_t);
    return H * (Jw(0) * w_t(0) + Jw(1) * w_t(1)) / (Jw(0) * Jw(0) + Jw(1) * Jw(1));
  }
  Eigen::Matrix3d R_IP(double alpha, const Eigen::Vector3d& w) const {
    return rotZ(alpha) * rotX(nutation(w)) * rotZ(spin(w));
  }
};

}  // namespace

TEST_CASE("Jacobi elliptic functions by the AGM", "[sim][body]") {
  const double m = 0.4;
  const double K = std::comp_ellint_1(std::sqrt(m));
  const Jacobi quarter = jacobi(K, m);
  CHECK(quarter.sn == Approx(1.0).epsilon(1e-14));
  CHECK(std::abs(quarter.cn) < 1e-13);
  CHECK(quarter.dn == Approx(std::sqrt(1.0 - m)).epsilon(1e-13));
  for (const double u : {-3.0, -0.4, 0.0, 0.7, 2.5, 11.0}) {
    const Jacobi f = jacobi(u, m);
    CHECK(f.sn * f.sn + f.cn * f.cn == Approx(1.0).epsilon(1e-14));
    const double h = 1e-5;  // d sn / du = cn dn
    CHECK((jacobi(u + h, m).sn - jacobi(u - h, m).sn) / (2.0 * h) == Approx(f.cn * f.dn).margin(1e-9));
    CHECK((jacobi(u + h, m).dn - jacobi(u - h, m).dn) / (2.0 * h) == Approx(-m * f.sn * f.cn).margin(1e-9));
    CHECK(jacobi(u, 0.0).sn == Approx(std::sin(u)).margin(1e-15));
  }
}

TEST_CASE("Torque-free asymmetric body follows the Jacobi elliptic solution", "[sim][body]") {
  GIVEN("J = diag(2, 3, 4) kg m² in a principal frame P turned against the body axes") {
    const Eigen::Vector3d moments(2.0, 3.0, 4.0);
    const Eigen::Matrix3d R_BP = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
    RigidBodyParams p;
    p.J_B_kg_m2 = R_BP * moments.asDiagonal() * R_BP.transpose();
    const RigidBodyWheels body(p);

    const Eigen::Vector3d w0_P(0.2, 0.1, 0.3);  // H² = 1.69 > 2T J2 = 1.41, m ≈ 0.253
    const EulerSolution exact(moments, w0_P);
    const Eigen::Quaterniond q0_NB = quatFromRotationVector(Eigen::Vector3d(0.3, -1.1, 0.6));
    RigidBodyState x{q0_NB, R_BP * w0_P, Eigen::Vector4d::Zero()};
    const Eigen::Vector3d H0_N = body.totalMomentum_N_Nms(x);
    // Inertial frame I with z along H: R_NI fixed by the attitude at t = 0 (α(0) = 0).
    const Eigen::Matrix3d R_NI = q0_NB.toRotationMatrix() * R_BP * exact.R_IP(0.0, w0_P).transpose();

    THEN("the analytic solution starts at the initial rate and on H") {
      CHECK(exact.m > 0.2);
      CHECK((exact.w(0.0) - w0_P).norm() < 1e-15);
      CHECK((R_NI.col(2) - H0_N.normalized()).norm() < 1e-14);
    }
    WHEN("integrated for 1000 s (≈ 26 nutation periods) as the rig runs: 0.1 s steps of 4 RK4 substeps") {
      constexpr double kStep = 0.1;
      constexpr int kSubsteps = 4;
      constexpr int kStepsPerCheck = 1000;  // compare every 100 s
      constexpr int kQuadraturePanels = 10000;  // Simpson panels per 100 s for α
      const auto no_torque = [](double, const RigidBodyState&) { return Eigen::Vector3d::Zero().eval(); };
      double alpha = 0.0;
      double max_rate_error = 0.0;
      double max_attitude_error = 0.0;
      double max_momentum_error = 0.0;
      for (int check = 0; check < 10; ++check) {
        const double t_start = check * kStepsPerCheck * kStep;
        for (int k = 0; k < kStepsPerCheck; ++k) {
          x = body.propagate(x, t_start + k * kStep, kStep, kSubsteps, Eigen::Vector4d::Zero(), no_torque);
        }
        const double t_end = t_start + kStepsPerCheck * kStep;
        const double h = (t_end - t_start) / kQuadraturePanels;  // composite Simpson for ∫α̇ dt
        double sum = exact.precessionRate(t_start) + exact.precessionRate(t_end);
        for (int i = 1; i < kQuadraturePanels; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * exact.precessionRate(t_start + i * h);
        alpha += sum * h / 3.0;

        const Eigen::Vector3d w_exact_P = exact.w(t_end);
        max_rate_error = std::max(max_rate_error, (R_BP.transpose() * x.w_NB_B - w_exact_P).norm());
        const Eigen::Matrix3d R_NB_exact = R_NI * exact.R_IP(alpha, w_exact_P) * R_BP.transpose();
        const Eigen::Quaterniond error(R_NB_exact.transpose() * x.q_NB.toRotationMatrix());
        max_attitude_error = std::max(max_attitude_error, rotationVectorFromQuat(error).norm());
        max_momentum_error = std::max(max_momentum_error, (body.totalMomentum_N_Nms(x) - H0_N).norm() / H0_N.norm());
      }
      THEN("body rates and attitude match to 1e-8 and H_N stays fixed") {
        CHECK(max_rate_error < 1e-8);      // [rad/s]
        CHECK(max_attitude_error < 1e-8);  // [rad]
        CHECK(max_momentum_error < 1e-10);  // RK4 is not symplectic: H drifts at O(h⁴)
      }
    }
  }
}
