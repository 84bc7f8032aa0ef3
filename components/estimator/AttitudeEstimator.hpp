// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace flatsat::estimator {

/// Gains of the explicit complementary filter and its bias integrator.
struct AttitudeEstimatorParams {
  double kp_per_s = 0.2;           // [1/s] attitude correction gain k_P, >= 0
  double ki_per_s2 = 0.002;        // [1/s²] gyro-bias integral gain k_I, >= 0
  double max_bias_rad_s = 0.02;    // [rad/s] clamp of each bias component (anti-windup), > 0
  bool use_magnetometer = true;    // [-] field corrects the filter after initialisation
  /// [-] no field source in the rig: initialise from the Sun alone (the smallest rotation
  /// taking the measured Sun onto the reference; the roll about the Sun line is then
  /// arbitrary, which Sun pointing does not need and seed S0 measures)
  bool sun_only_init = false;

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct AttitudeEstimatorInput {
  Eigen::Vector3d w_gyro_B_rad_s = Eigen::Vector3d::Zero();   // [rad/s] measured body rate
  Eigen::Vector3d sun_B_meas_unit = Eigen::Vector3d::Zero();  // [-] measured Sun direction, body
  bool sun_valid = false;                                     // sun sensor sees the Sun
  Eigen::Vector3d b_B_meas_T = Eigen::Vector3d::Zero();       // [T] measured field, body
  bool b_valid = false;                                       // magnetometer sample usable
  Eigen::Vector3d sun_N_ref_unit = Eigen::Vector3d::Zero();   // [-] onboard-model Sun direction, inertial
  Eigen::Vector3d b_N_ref_T = Eigen::Vector3d::Zero();        // [T] onboard-model field, inertial
};

struct AttitudeEstimatorOutput {
  Eigen::Quaterniond q_NB = Eigen::Quaterniond::Identity();        // [-] body → inertial (Hamilton)
  Eigen::Vector3d w_NB_B_rad_s = Eigen::Vector3d::Zero();          // [rad/s] gyro minus bias estimate
  Eigen::Vector3d gyro_bias_B_rad_s = Eigen::Vector3d::Zero();     // [rad/s] bias estimate
  Eigen::Vector3d sun_B_est_unit = Eigen::Vector3d::Zero();        // [-] R(q)ᵀ sun_N_ref; zero until initialised
  bool initialized = false;   // attitude known (TRIAD has run)
  bool sun_used = false;      // Sun entered this step (TRIAD or correction)
  bool field_used = false;    // field entered this step (TRIAD or correction)
  bool bias_clamped = false;  // the bias integrator hit ±max_bias_rad_s this step
};

/// Attitude from Sun + field vectors and a gyro.
///
/// Initialisation: TRIAD with the Sun as the primary (exactly matched) vector (Shuster & Oh
/// 1981, J. Guidance and Control 4(1); Markley & Crassidis 2014, §5.2). It needs a valid Sun
/// and field pair, not nearly parallel, in the same step; until then the output is identity.
/// Afterwards: the explicit complementary filter with bias estimation of Mahony, Hamel &
/// Pflimlin 2008 (IEEE TAC 53(5), Eq. 32), corrected by whichever vectors are valid; with
/// none (eclipse and no field) it propagates on the bias-corrected gyro.
/// Everything the filter carries from one step to the next: a checkpoint of it lets a
/// restarted estimator go on where the old one stopped.
struct AttitudeEstimatorState {
  Eigen::Quaterniond q_NB = Eigen::Quaterniond::Identity();  // [-] body to inertial, Hamilton
  Eigen::Vector3d bias_B_rad_s = Eigen::Vector3d::Zero();    // [rad/s] gyro bias estimate
  bool initialized = false;                                  // [-] TRIAD done
  std::int64_t last_t_ns = 0;                                // [ns] previous step's sample time
  bool has_last_t = false;                                   // [-] last_t_ns holds one
};

class AttitudeEstimator {
 public:
  using State = AttitudeEstimatorState;
  using Params = AttitudeEstimatorParams;
  using Input = AttitudeEstimatorInput;
  using Output = AttitudeEstimatorOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit AttitudeEstimator(const Params& params);

  /// Back to uninitialised: identity attitude, zero bias, no previous time.
  void reset();

  /// @param t_ns [ns] sample time; the difference to the previous call is the integration step.
  Output step(const Input& in, std::int64_t t_ns);

  const Params& params() const { return params_; }

  State state() const { return {q_NB_, bias_B_rad_s_, initialized_, last_t_ns_, has_last_t_}; }
  /// Continues from `state` (a checkpoint); the next step propagates from its last_t_ns.
  void restore(const State& state);

 private:
  Params params_;
  Eigen::Quaterniond q_NB_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d bias_B_rad_s_ = Eigen::Vector3d::Zero();
  bool initialized_ = false;
  std::int64_t last_t_ns_ = 0;
  bool has_last_t_ = false;
};

/// [-] sine of the smallest angle between the two TRIAD vectors (≈ 1°): closer pairs leave
/// the roll about the primary vector ill-defined.
inline constexpr double kMinTriadSine = 0.0175;

/// TRIAD: the rotation R_NB with R_NB·v1_B = v1_N exactly and v2 matched as well as the pair
/// allows. Inputs need not be unit. Returns false (leaving q_NB) when either pair is closer
/// to parallel than kMinTriadSine.
bool triad(const Eigen::Vector3d& v1_B, const Eigen::Vector3d& v2_B, const Eigen::Vector3d& v1_N,
           const Eigen::Vector3d& v2_N, Eigen::Quaterniond& q_NB);

}  // namespace flatsat::estimator
