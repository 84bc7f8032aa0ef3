// SPDX-License-Identifier: Apache-2.0
#include "components/star_tracker/StarTrackerModel.hpp"

#include <cmath>
#include <stdexcept>

#include "components/common/Validation.hpp"

namespace flatsat::star_tracker {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kEarthRadius_m = 6378137.0;  // WGS-84 equatorial radius: the limb seen from orbit

double angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}
}  // namespace

std::vector<std::string> StarTrackerParams::validate() const {
  std::vector<std::string> e;
  if (!(std::abs(q_body_sensor.norm() - 1.0) < 1e-6)) e.push_back("q_body_sensor: must be a unit quaternion");
  if (q_body_sensor_onboard && !(std::abs(q_body_sensor_onboard->norm() - 1.0) < 1e-6)) {
    e.push_back("q_body_sensor_onboard: must be a unit quaternion");
  }
  if (!(noise_cross_rad >= 0.0 && std::isfinite(noise_cross_rad))) e.push_back("noise_cross_rad: must be >= 0");
  if (!(noise_about_rad >= 0.0 && std::isfinite(noise_about_rad))) e.push_back("noise_about_rad: must be >= 0");
  if (!(max_rate_rad_s > 0.0 && std::isfinite(max_rate_rad_s))) e.push_back("max_rate_rad_s: must be > 0");
  if (!(sun_exclusion_rad >= 0.0 && sun_exclusion_rad < kPi)) e.push_back("sun_exclusion_rad: must be in [0, pi)");
  if (!(earth_exclusion_rad >= 0.0 && earth_exclusion_rad < kPi)) e.push_back("earth_exclusion_rad: must be in [0, pi)");
  return e;
}

StarTrackerModel::StarTrackerModel(const Params& params)
    : params_(validated(params, "star tracker")),
      R_BS_(params.q_body_sensor.normalized().toRotationMatrix()),
      noise_(params.seed) {
  // The unit reports q_NS ⊗ n_S (n: its noise); flight software takes
  // q_NB_measured = q_NS ⊗ n_S ⊗ q_BS_onboard⁻¹ = q_NB ⊗ n_B ⊗ (q_BS ⊗ q_BS_onboard⁻¹), n_B = q_BS ⊗ n_S ⊗ q_BS⁻¹.
  const auto& onboard = params.q_body_sensor_onboard;
  if (onboard && !onboard->coeffs().isApprox(params.q_body_sensor.coeffs(), 0.0)) {
    misalignment_ = (params.q_body_sensor.normalized() * onboard->normalized().conjugate()).normalized();
  }
}

void StarTrackerModel::reset() { noise_.reset(); }

StarTrackerOutput StarTrackerModel::step(const Input& in, std::int64_t) {
  Output out;
  out.q_NB_true = in.q_NB.normalized();
  const Eigen::Vector3d error_S{noise_.sample(params_.noise_cross_rad), noise_.sample(params_.noise_cross_rad),
                                noise_.sample(params_.noise_about_rad)};
  out.error_B_rad = R_BS_ * error_S;
  if (misalignment_) {
    const Eigen::AngleAxisd total(applyError(Eigen::Quaterniond::Identity(), out.error_B_rad) * *misalignment_);
    out.error_B_rad = total.angle() * total.axis();
  }

  const Eigen::Vector3d boresight_B = R_BS_.col(2);
  const Eigen::Vector3d nadir_B = out.q_NB_true.conjugate() * (-in.r_N_m.normalized());
  const double earth_radius_angle = std::asin(std::min(1.0, kEarthRadius_m / in.r_N_m.norm()));
  const bool rate_ok = in.w_B_rad_s.norm() <= params_.max_rate_rad_s;
  const bool sun_ok = in.illumination <= 0.0 || angle(boresight_B, in.sun_B_unit) >= params_.sun_exclusion_rad;
  const bool earth_ok = angle(boresight_B, nadir_B) - earth_radius_angle >= params_.earth_exclusion_rad;
  out.valid = rate_ok && sun_ok && earth_ok;
  return out;
}

Eigen::Quaterniond applyError(const Eigen::Quaterniond& q_NB, const Eigen::Vector3d& error_B_rad) {
  const double a = error_B_rad.norm();
  const Eigen::Quaterniond dq =
      a > 0.0 ? Eigen::Quaterniond(Eigen::AngleAxisd(a, error_B_rad / a)) : Eigen::Quaterniond::Identity();
  return (q_NB * dq).normalized();
}

}  // namespace flatsat::star_tracker
