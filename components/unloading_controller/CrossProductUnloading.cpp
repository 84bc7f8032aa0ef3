// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/CrossProductUnloading.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

namespace flatsat::unloading_controller {

namespace {
constexpr double kUnitTolerance = 1e-6;
}  // namespace

std::vector<std::string> CrossProductUnloadingParams::validate() const {
  std::vector<std::string> errors;
  if (!(gain_per_s > 0.0) || !std::isfinite(gain_per_s)) {
    errors.emplace_back("gain_per_s: must be finite and > 0");
  }
  if (!max_dipole_Am2.allFinite() || !(max_dipole_Am2.minCoeff() > 0.0)) {
    errors.emplace_back("max_dipole_Am2: every coil must be finite and > 0");
  }
  if (wheel_count < 1 || wheel_count > 4) {
    errors.emplace_back("wheel_count: must be in 1..4");
  } else {
    for (int i = 0; i < wheel_count; ++i) {
      const Eigen::Vector3d a = wheel_axes_B.col(i);
      if (!a.allFinite() || !(std::abs(a.norm() - 1.0) <= kUnitTolerance)) {
        errors.emplace_back("wheel_axes_B: column " + std::to_string(i) + " must be a unit vector");
      }
      if (!(wheel_inertia_kg_m2[i] > 0.0) || !std::isfinite(wheel_inertia_kg_m2[i])) {
        errors.emplace_back("wheel_inertia_kg_m2: wheel " + std::to_string(i) + " must be finite and > 0");
      }
    }
  }
  if (!h_target_B_Nms.allFinite()) {
    errors.emplace_back("h_target_B_Nms: must be finite");
  }
  if (!(h_stop_Nms >= 0.0) || !std::isfinite(h_stop_Nms)) {
    errors.emplace_back("h_stop_Nms: must be finite and >= 0");
  }
  if (!(h_start_Nms >= h_stop_Nms) || !std::isfinite(h_start_Nms)) {
    errors.emplace_back("h_start_Nms: must be finite and >= h_stop_Nms");
  }
  if (!(min_field_T > 0.0) || !std::isfinite(min_field_T)) {
    errors.emplace_back("min_field_T: must be finite and > 0");
  }
  return errors;
}

CrossProductUnloading::CrossProductUnloading(const Params& params) : params_(params) {
  if (const auto errors = params_.validate(); !errors.empty()) {
    std::string message = "CrossProductUnloadingParams invalid:";
    for (const auto& e : errors) {
      message += " " + e + ";";
    }
    throw std::invalid_argument(message);
  }
}

void CrossProductUnloading::reset() { unloading_ = false; }

CrossProductUnloadingOutput CrossProductUnloading::step(const Input& in, std::int64_t /*t_ns*/) {
  const int n = params_.wheel_count;
  Output out;
  out.h_B_Nms = params_.wheel_axes_B.leftCols(n) *
                    params_.wheel_inertia_kg_m2.head(n).cwiseProduct(in.wheel_speed_rad_s.head(n)) -
                params_.h_target_B_Nms;

  // Hysteresis keeps the coils from chattering around a single threshold; with both
  // thresholds 0 unloading runs whenever there is momentum to dump.
  const double h_norm = out.h_B_Nms.norm();
  if (h_norm > params_.h_start_Nms) {
    unloading_ = true;
  } else if (h_norm < params_.h_stop_Nms) {
    unloading_ = false;
  }

  const double b_sq = in.b_B_T.squaredNorm();
  if (!in.b_valid || !(b_sq >= params_.min_field_T * params_.min_field_T) || !std::isfinite(b_sq)) {
    return out;
  }
  out.h_perp_B_Nms = out.h_B_Nms - in.b_B_T * (in.b_B_T.dot(out.h_B_Nms) / b_sq);
  if (!params_.enabled || !unloading_) {
    return out;
  }

  // M = k (H × B)/|B|²; (H × B) × B = −|B|² H⊥, hence M × B = −k H⊥.
  Eigen::Vector3d m = params_.gain_per_s * out.h_B_Nms.cross(in.b_B_T) / b_sq;
  // One common factor for all coils keeps the torque direction −H⊥ (only its size shrinks).
  const double scale = (params_.max_dipole_Am2.array() / m.array().abs()).minCoeff();
  if (scale < 1.0) {
    m *= scale;
    out.saturated = true;
  }
  out.m_B_Am2 = m;
  out.active = true;
  return out;
}

}  // namespace flatsat::unloading_controller
