// SPDX-License-Identifier: Apache-2.0
#include "sim/Attitude.hpp"

#include <cmath>

namespace flatsat::sim {
namespace {

// Below these magnitudes the closed forms lose digits to cancellation or
// divide by ~0; the Taylor series used instead are exact to double precision.
constexpr double kSmallAngle_rad = 1e-6;
constexpr double kSmallVectorNorm = 1e-8;

}  // namespace

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(),  //
      a.z(), 0.0, -a.x(),   //
      -a.y(), a.x(), 0.0;
  return m;
}

Eigen::Quaterniond quatFromRotationVector(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  // sin(θ/2)/θ = ½ − θ²/48 + O(θ⁴).
  const double k = angle > kSmallAngle_rad ? std::sin(0.5 * angle) / angle : 0.5 - angle * angle / 48.0;
  const Eigen::Vector3d v = k * phi;
  return Eigen::Quaterniond(std::cos(0.5 * angle), v.x(), v.y(), v.z());
}

Eigen::Vector3d rotationVectorFromQuat(const Eigen::Quaterniond& q) {
  // q and −q are the same rotation; w ≥ 0 picks the one with angle ≤ π.
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  const double w = sign * q.w();
  const Eigen::Vector3d v = sign * q.vec();
  const double n = v.norm();
  // 2·atan2(n, w)/n = (2/w)(1 − n²/(3w²)) + O(n⁴) for small n.
  const double k = n > kSmallVectorNorm ? 2.0 * std::atan2(n, w) / n : (2.0 / w) * (1.0 - n * n / (3.0 * w * w));
  return k * v;
}

Eigen::Quaterniond quatDerivative(const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& w_NB_B) {
  const Eigen::Quaterniond product = q_NB * Eigen::Quaterniond(0.0, w_NB_B.x(), w_NB_B.y(), w_NB_B.z());
  return Eigen::Quaterniond(0.5 * product.coeffs());
}

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  // atan2 keeps full precision near 0 and π, where acos of the dot product does not.
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

Eigen::Matrix3d rot3(double angle_rad) {
  const double c = std::cos(angle_rad);
  const double s = std::sin(angle_rad);
  Eigen::Matrix3d r;
  r << c, s, 0.0,  //
      -s, c, 0.0,  //
      0.0, 0.0, 1.0;
  return r;
}

}  // namespace flatsat::sim
