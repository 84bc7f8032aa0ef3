// SPDX-License-Identifier: Apache-2.0
#include "components/unloading_controller/CrossProductUnloading.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

#include "components/common/Validation.hpp"

namespace flatsat::unloading_controller {

std::vector<std::string> CrossProductUnloadingParams::validate() const {
  std::vector<std::string> errors;
  requirePositive(errors, "gain_per_s", gain_per_s);
  requireAllPositive(errors, "max_dipole_Am2", max_dipole_Am2, "coil");
  append(errors, wheels.validate("wheels"));
  requireFinite(errors, "h_target_B_Nms", h_target_B_Nms);
  requireNonNegative(errors, "h_stop_Nms", h_stop_Nms);
  require(errors, h_start_Nms >= h_stop_Nms && std::isfinite(h_start_Nms), "h_start_Nms",
          "must be finite and >= h_stop_Nms");
  requirePositive(errors, "min_field_T", min_field_T);
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

void CrossProductUnloading::retune(const Params& params) { params_ = validated(params, "CrossProductUnloadingParams"); }

CrossProductUnloadingOutput CrossProductUnloading::step(const Input& in, std::int64_t /*t_ns*/) {
  Output out;
  out.h_B_Nms = params_.wheels.momentum_B_Nms(in.wheel_speed_rad_s) - params_.h_target_B_Nms;

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
