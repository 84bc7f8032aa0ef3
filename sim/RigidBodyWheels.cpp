// SPDX-License-Identifier: Apache-2.0
#include "sim/RigidBodyWheels.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "sim/Attitude.hpp"
#include "sim/Format.hpp"

namespace flatsat::sim {
namespace {

// Relative tolerances for properties that are exact on paper but arrive as
// rounded decimal inputs (symmetry, unit axes, a thin rod's λ1 + λ2 = λ3).
constexpr double kSymmetryTolerance = 1e-9;
constexpr double kAxisNormTolerance = 1e-6;
constexpr double kTriangleTolerance = 1e-9;

std::string indexed(const char* field, int i) { return std::string(field) + "[" + std::to_string(i) + "]"; }

void validateInertia(const Eigen::Matrix3d& J, std::vector<std::string>& errors) {
  if (!J.allFinite()) {
    errors.push_back("J_B_kg_m2: must be finite");
    return;
  }
  if ((J - J.transpose()).norm() > kSymmetryTolerance * J.norm()) {
    errors.push_back("J_B_kg_m2: must be symmetric");
    return;
  }
  const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(J).eigenvalues();  // ascending
  if (moments(0) <= 0.0) {
    errors.push_back("J_B_kg_m2: must be positive definite (smallest principal moment " + formatNumber(moments(0)) +
                     " kg m²)");
  } else if (moments(0) + moments(1) < moments(2) * (1.0 - kTriangleTolerance)) {
    errors.push_back("J_B_kg_m2: principal moments " + formatNumber(moments(0)) + ", " + formatNumber(moments(1)) +
                     ", " + formatNumber(moments(2)) + " kg m² violate the triangle inequality J1 + J2 ≥ J3");
  }
}

}  // namespace

std::vector<std::string> RigidBodyParams::validate() const {
  std::vector<std::string> errors;
  validateInertia(J_B_kg_m2, errors);
  if (wheel_count < 0 || wheel_count > kMaxWheels) {
    errors.push_back("wheel_count: " + std::to_string(wheel_count) + " not in 0.." + std::to_string(kMaxWheels));
    return errors;
  }
  Eigen::Matrix3d J_spinless = J_B_kg_m2;
  for (int i = 0; i < wheel_count; ++i) {
    const Eigen::Vector3d axis = wheel_axes_B.col(i);
    if (!axis.allFinite() || std::abs(axis.norm() - 1.0) > kAxisNormTolerance) {
      errors.push_back(indexed("wheel_axes_B", i) + ": must be a unit vector (norm " + formatNumber(axis.norm()) + ")");
    }
    if (!(wheel_inertia_kg_m2(i) > 0.0) || !std::isfinite(wheel_inertia_kg_m2(i))) {
      errors.push_back(indexed("wheel_inertia_kg_m2", i) + ": " + formatNumber(wheel_inertia_kg_m2(i)) +
                       " must be > 0");
    }
    if (!(wheel_max_torque_Nm(i) > 0.0) || !std::isfinite(wheel_max_torque_Nm(i))) {
      errors.push_back(indexed("wheel_max_torque_Nm", i) + ": " + formatNumber(wheel_max_torque_Nm(i)) +
                       " must be > 0");
    }
    if (!(wheel_max_momentum_Nms(i) > 0.0) || !std::isfinite(wheel_max_momentum_Nms(i))) {
      errors.push_back(indexed("wheel_max_momentum_Nms", i) + ": " + formatNumber(wheel_max_momentum_Nms(i)) +
                       " must be > 0");
    }
    if (!(wheel_viscous_friction_Nms_rad(i) >= 0.0) || !std::isfinite(wheel_viscous_friction_Nms_rad(i))) {
      errors.push_back(indexed("wheel_viscous_friction_Nms_rad", i) + ": " +
                       formatNumber(wheel_viscous_friction_Nms_rad(i)) + " must be ≥ 0");
    }
    if (!(wheel_coulomb_friction_Nm(i) >= 0.0) || !std::isfinite(wheel_coulomb_friction_Nm(i))) {
      errors.push_back(indexed("wheel_coulomb_friction_Nm", i) + ": " + formatNumber(wheel_coulomb_friction_Nm(i)) +
                       " must be ≥ 0");
    }
    J_spinless -= wheel_inertia_kg_m2(i) * axis * axis.transpose();
  }
  if (errors.empty() && Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(J_spinless).eigenvalues()(0) <= 0.0) {
    errors.push_back("wheel_inertia_kg_m2: J minus the rotors' axial inertia must stay positive definite");
  }
  return errors;
}

RigidBodyWheels::RigidBodyWheels(const RigidBodyParams& params)
    : params_(params),
      active_(Eigen::Vector4d::Zero()),
      A_(Eigen::Matrix<double, 3, kMaxWheels>::Zero()),
      inertia_(Eigen::Vector4d::Zero()),
      viscous_(Eigen::Vector4d::Zero()),
      coulomb_(Eigen::Vector4d::Zero()),
      inverse_effective_inertia_(Eigen::Vector4d::Zero()),
      J_spinless_(params.J_B_kg_m2) {
  for (int i = 0; i < params.wheel_count; ++i) {
    active_(i) = 1.0;
    A_.col(i) = params.wheel_axes_B.col(i);
    inertia_(i) = params.wheel_inertia_kg_m2(i);
    viscous_(i) = params.wheel_viscous_friction_Nms_rad(i);
    coulomb_(i) = params.wheel_coulomb_friction_Nm(i);
    J_spinless_ -= inertia_(i) * A_.col(i) * A_.col(i).transpose();
  }
  J_spinless_inv_ = J_spinless_.inverse();
  A_pinv_ = A_.completeOrthogonalDecomposition().pseudoInverse();
  for (int i = 0; i < params.wheel_count; ++i) {
    inverse_effective_inertia_(i) = 1.0 / inertia_(i) + A_.col(i).dot(J_spinless_inv_ * A_.col(i));
  }
}

RigidBodyState RigidBodyWheels::makeState(const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& w_NB_B,
                                          const Eigen::Vector4d& wheel_speeds_rad_s) const {
  const Eigen::Vector4d absolute_rate = wheel_speeds_rad_s + A_.transpose() * w_NB_B;
  return RigidBodyState{q_NB.normalized(), w_NB_B, inertia_.cwiseProduct(absolute_rate)};
}

Eigen::Vector4d RigidBodyWheels::wheelSpeeds_rad_s(const RigidBodyState& x) const {
  Eigen::Vector4d speeds = Eigen::Vector4d::Zero();
  for (int i = 0; i < params_.wheel_count; ++i) speeds(i) = x.h_wheels_Nms(i) / inertia_(i) - A_.col(i).dot(x.w_NB_B);
  return speeds;
}

Eigen::Vector3d RigidBodyWheels::wheelMomentum_B_Nms(const RigidBodyState& x) const {
  return A_ * inertia_.cwiseProduct(wheelSpeeds_rad_s(x));
}

Eigen::Vector3d RigidBodyWheels::totalMomentum_N_Nms(const RigidBodyState& x) const {
  return x.q_NB * (J_spinless_ * x.w_NB_B + A_ * x.h_wheels_Nms);
}

RigidBodyState RigidBodyWheels::heldAt(const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& w_NB_B,
                                       const Eigen::Vector3d& H_N_Nms) const {
  RigidBodyState x;
  x.q_NB = q_NB.normalized();
  x.w_NB_B = w_NB_B;
  const Eigen::Vector3d in_wheels_B = x.q_NB.conjugate() * H_N_Nms - J_spinless_ * w_NB_B;
  x.h_wheels_Nms = A_pinv_ * in_wheels_B;
  return x;
}

double RigidBodyWheels::kineticEnergy_J(const RigidBodyState& x) const {
  double energy = 0.5 * x.w_NB_B.dot(J_spinless_ * x.w_NB_B);
  for (int i = 0; i < params_.wheel_count; ++i) energy += 0.5 * x.h_wheels_Nms(i) * x.h_wheels_Nms(i) / inertia_(i);
  return energy;
}

Eigen::Vector4d RigidBodyWheels::frictionTorque_Nm(const RigidBodyState& x, double substep_s) const {
  const Eigen::Vector4d speeds = wheelSpeeds_rad_s(x);
  Eigen::Vector4d tau = Eigen::Vector4d::Zero();
  for (int i = 0; i < params_.wheel_count; ++i) {
    const double speed = speeds(i);
    const double band = coulomb_(i) * substep_s * inverse_effective_inertia_(i);
    const double dry = std::abs(speed) < band ? speed / band : static_cast<double>((speed > 0.0) - (speed < 0.0));
    tau(i) = -viscous_(i) * speed - coulomb_(i) * dry;
  }
  return tau;
}

Eigen::Vector4d RigidBodyWheels::limitMotorTorque(const RigidBodyState& x, const Eigen::Vector4d& tau_cmd_Nm) const {
  const Eigen::Vector4d relative_momentum = inertia_.cwiseProduct(wheelSpeeds_rad_s(x));
  Eigen::Vector4d tau = Eigen::Vector4d::Zero();
  for (int i = 0; i < params_.wheel_count; ++i) {
    if (!std::isfinite(tau_cmd_Nm(i))) continue;
    const double limit = params_.wheel_max_torque_Nm(i);
    tau(i) = std::clamp(tau_cmd_Nm(i), -limit, limit);
    const double h_max = params_.wheel_max_momentum_Nms(i);
    if ((relative_momentum(i) >= h_max && tau(i) > 0.0) || (relative_momentum(i) <= -h_max && tau(i) < 0.0)) {
      tau(i) = 0.0;
    }
  }
  return tau;
}

RigidBodyWheels::Derivative RigidBodyWheels::derivative(const RigidBodyState& x, const Eigen::Vector3d& tau_ext_B_Nm,
                                                        const Eigen::Vector4d& tau_motor_Nm, double substep_s) const {
  const Eigen::Vector4d tau_axial = tau_motor_Nm.cwiseProduct(active_) + frictionTorque_Nm(x, substep_s);
  const Eigen::Vector3d H_B = J_spinless_ * x.w_NB_B + A_ * x.h_wheels_Nms;
  return Derivative{quatDerivative(x.q_NB, x.w_NB_B).coeffs(),
                    J_spinless_inv_ * (tau_ext_B_Nm - x.w_NB_B.cross(H_B) - A_ * tau_axial), tau_axial};
}

RigidBodyState RigidBodyWheels::advanced(const RigidBodyState& x, const Derivative& k, double dt_s) {
  RigidBodyState next;
  next.q_NB.coeffs() = x.q_NB.coeffs() + dt_s * k.q_dot;
  next.q_NB.normalize();
  next.w_NB_B = x.w_NB_B + dt_s * k.w_dot;
  next.h_wheels_Nms = x.h_wheels_Nms + dt_s * k.h_dot;
  return next;
}

RigidBodyWheels::Derivative RigidBodyWheels::rk4Average(const Derivative& k1, const Derivative& k2,
                                                        const Derivative& k3, const Derivative& k4) {
  return Derivative{(k1.q_dot + 2.0 * k2.q_dot + 2.0 * k3.q_dot + k4.q_dot) / 6.0,
                    (k1.w_dot + 2.0 * k2.w_dot + 2.0 * k3.w_dot + k4.w_dot) / 6.0,
                    (k1.h_dot + 2.0 * k2.h_dot + 2.0 * k3.h_dot + k4.h_dot) / 6.0};
}

}  // namespace flatsat::sim
