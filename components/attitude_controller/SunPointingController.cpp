// SPDX-License-Identifier: Apache-2.0
#include "components/attitude_controller/SunPointingController.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

#include "components/common/Validation.hpp"
#include "sim/Frames.hpp"

namespace flatsat::attitude_controller {

std::vector<std::string> SunPointingControllerParams::validate() const {
  std::vector<std::string> errors;
  requirePositive(errors, "kp_Nm_per_rad", kp_Nm_per_rad);
  requirePositive(errors, "kd_Nm_s_per_rad", kd_Nm_s_per_rad);
  requirePositive(errors, "max_torque_Nm", max_torque_Nm);
  requirePositive(errors, "max_rate_rad_s", max_rate_rad_s);
  requireUnit(errors, "pointing_axis_B", pointing_axis_B);
  append(errors, wheels.validate("wheels"));
  return errors;
}

SunPointingController::SunPointingController(const Params& params)
    : params_(params), A_B_(Eigen::Matrix<double, 3, 4>::Zero()),
      A_pinv_(Eigen::Matrix<double, 4, 3>::Zero()),
      max_error_rad_(params.max_rate_rad_s * params.kd_Nm_s_per_rad / params.kp_Nm_per_rad) {
  if (const auto errors = params_.validate(); !errors.empty()) {
    std::string message = "SunPointingControllerParams invalid:";
    for (const auto& e : errors) {
      message += " " + e + ";";
    }
    throw std::invalid_argument(message);
  }
  const int n = params_.wheels.count;
  A_B_ = params_.wheels.liveAxes_B();
  // Minimum-norm least-squares inverse: exact torque with ≥ 3 independent axes, the closest
  // achievable torque with fewer (a failed-wheel configuration).
  const Eigen::MatrixXd A = A_B_.leftCols(n);
  A_pinv_.topRows(n) = A.completeOrthogonalDecomposition().pseudoInverse();
}

void SunPointingController::reset() {}

SunPointingControllerOutput SunPointingController::step(const Input& in, std::int64_t /*t_ns*/) {
  const double sun_norm = in.sun_B_est_unit.norm();
  if (!in.valid || !(sun_norm > 0.0)) {
    return Output{};
  }
  const Eigen::Vector3d s = in.sun_B_est_unit / sun_norm;
  const Eigen::Vector3d& a = params_.pointing_axis_B;
  const Eigen::Vector3d c = a.cross(s);
  const double sin_angle = c.norm();
  const double angle = std::atan2(sin_angle, a.dot(s));
  // Exactly anti-parallel: every axis normal to a is a shortest rotation; any one will do.
  const Eigen::Vector3d e_axis = sin_angle > 0.0 ? Eigen::Vector3d(c / sin_angle) : a.unitOrthogonal();
  return regulate(angle, e_axis, in.w_NB_B_rad_s, in.w_NB_B_rad_s, in.wheel_speed_rad_s);
}

SunPointingControllerOutput SunPointingController::hold(const AttitudeTargetInput& in, std::int64_t /*t_ns*/) {
  if (!in.valid) return Output{};
  // q_BT = q_NB* q_NT: the target seen from the body; its shorter rotation (w >= 0).
  Eigen::Quaterniond q_BT = in.q_NB_est.normalized().conjugate() * in.q_NT.normalized();
  if (q_BT.w() < 0.0) q_BT.coeffs() = -q_BT.coeffs();
  const double sin_half = q_BT.vec().norm();
  const double angle = 2.0 * std::atan2(sin_half, q_BT.w());
  const Eigen::Vector3d axis = sin_half > 0.0 ? Eigen::Vector3d(q_BT.vec() / sin_half) : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d w_target_B = in.q_NB_est.normalized().conjugate() * in.w_NT_N_rad_s;
  return regulate(angle, axis, in.w_NB_B_rad_s - w_target_B, in.w_NB_B_rad_s, in.wheel_speed_rad_s);
}

SunPointingControllerOutput SunPointingController::regulate(double angle_rad, const Eigen::Vector3d& axis_B,
                                                            const Eigen::Vector3d& w_error_B_rad_s,
                                                            const Eigen::Vector3d& w_NB_B_rad_s,
                                                            const Eigen::Vector4d& wheel_speed_rad_s) const {
  Output out;
  out.rate_limited = angle_rad > max_error_rad_;
  const Eigen::Vector3d e = std::min(angle_rad, max_error_rad_) * axis_B;
  const Eigen::Vector3d h_wheels_B = params_.wheels.momentum_B_Nms(wheel_speed_rad_s);
  Eigen::Vector3d tau = params_.kp_Nm_per_rad * e - params_.kd_Nm_s_per_rad * w_error_B_rad_s +
                        w_NB_B_rad_s.cross(h_wheels_B);
  const double tau_norm = tau.norm();
  if (tau_norm > params_.max_torque_Nm) {
    tau *= params_.max_torque_Nm / tau_norm;
    out.saturated = true;
  }
  out.wheel_torque_Nm = -A_pinv_ * tau;
  out.tau_cmd_B_Nm = -A_B_ * out.wheel_torque_Nm;
  out.pointing_error_rad = angle_rad;
  return out;
}

AttitudeTargetInput s2OrbitalTarget(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s) {
  AttitudeTargetInput target;
  target.q_NT = Eigen::Quaterniond(sim::R_N_S2Orbital(r_N_m, v_N_m_s));
  target.w_NT_N_rad_s = r_N_m.cross(v_N_m_s) / r_N_m.squaredNorm();
  return target;
}

}  // namespace flatsat::attitude_controller
