// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "components/common/WheelGeometry.hpp"

namespace flatsat::unloading_controller {

/// Gain, coil limits, wheel geometry and hysteresis of the momentum-unloading law.
struct CrossProductUnloadingParams {
  double gain_per_s = 0.01;  // [1/s] k: decay rate of H⊥, > 0
  Eigen::Vector3d max_dipole_Am2 = Eigen::Vector3d::Constant(0.2);  // [A·m²] per-coil limit, > 0
  WheelGeometry wheels;      // [-] live wheels, spin axes, rotor inertias (see WheelGeometry)
  Eigen::Vector3d h_target_B_Nms = Eigen::Vector3d::Zero();  // [Nms] momentum to keep, finite
  double h_start_Nms = 0.0;     // [Nms] |H − h_target| above which unloading starts, >= h_stop_Nms
  double h_stop_Nms = 0.0;      // [Nms] |H − h_target| below which it stops, >= 0
  bool enabled = true;          // [-] false: "unloading off", zero dipole
  double min_field_T = 1.0e-6;  // [T] |B| below this: no command (M ∝ 1/|B|²), > 0

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct CrossProductUnloadingInput {
  Eigen::Vector4d wheel_speed_rad_s = Eigen::Vector4d::Zero();  // [rad/s] tachometer speeds
  Eigen::Vector3d b_B_T = Eigen::Vector3d::Zero();              // [T] field, body axes
  bool b_valid = false;                                         // field usable
};

struct CrossProductUnloadingOutput {
  Eigen::Vector3d m_B_Am2 = Eigen::Vector3d::Zero();        // [A·m²] dipole command
  Eigen::Vector3d h_B_Nms = Eigen::Vector3d::Zero();        // [Nms] excess momentum H − h_target
  Eigen::Vector3d h_perp_B_Nms = Eigen::Vector3d::Zero();   // [Nms] part of it ⊥ B; zero without field
  bool active = false;      // a dipole is commanded this step (enabled, hysteresis on, field usable)
  bool saturated = false;   // the dipole was scaled down to the coil limits
};

/// Cross-product momentum unloading (Singer 1964; flatsat spec algorithms.md, "The unloading
/// law"): M = k (H × B)/|B|², so the magnetic torque M × B = −k H⊥ drains the momentum
/// normal to the field. H = Σ a_i I_i Ω_i − h_target from the tachometers.
class CrossProductUnloading {
 public:
  using Params = CrossProductUnloadingParams;
  using Input = CrossProductUnloadingInput;
  using Output = CrossProductUnloadingOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit CrossProductUnloading(const Params& params);

  /// Hysteresis back to "not unloading".
  void reset();

  /// New gain, thresholds or limits, the hysteresis state kept (a change in flight).
  /// @throws std::invalid_argument listing every violation of params.validate().
  void retune(const Params& params);

  /// The law does not depend on time; t_ns [ns] is kept for the common API.
  Output step(const Input& in, std::int64_t t_ns);

  const Params& params() const { return params_; }

 private:
  Params params_;
  bool unloading_ = false;  // hysteresis state
};

}  // namespace flatsat::unloading_controller
