// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace flatsat::estimator {

/// Noise model and gates of the multiplicative EKF.
struct MekfParams {
  double gyro_arw_rad_per_sqrt_s = 2.9e-6;      // [rad/√s] angle random walk σ_v, > 0
  double gyro_rrw_rad_per_s_sqrt_s = 1.0e-9;    // [rad/s/√s] rate random walk σ_u, > 0
  double sun_sigma_rad = 1.75e-4;               // [rad] Sun direction 1σ per transverse axis, > 0
  double magnetometer_noise_T = 5.0e-8;         // [T] magnetometer 1σ white noise per axis, > 0
  double field_model_sigma_rad = 1.0e-3;        // [rad] 1σ direction error of the onboard field model and residual calibration, >= 0
  double magnetometer_bias_sigma_T = 5.0e-8;    // [T] 1σ per axis of the magnetometer's residual bias before estimation, > 0
  double magnetometer_bias_rw_T_per_sqrt_s = 0.0;  // [T/√s] random walk of that bias (temperature drift), >= 0
  Eigen::Vector3d star_tracker_sigma_B_rad{2.0e-5, 2.0e-5, 1.5e-4};  // [rad] star tracker 1σ about each body axis, each > 0
  double initial_attitude_sigma_rad = 0.02;     // [rad] 1σ per axis after TRIAD, > 0
  double initial_bias_sigma_rad_s = 1.0e-4;     // [rad/s] 1σ per axis of the first bias guess (0), > 0
  double gate_probability = 0.9999;             // [-] innovation inside the gate with this probability, (0, 1)
  double max_attitude_sigma_rad = 0.05;         // [rad] largest attitude 1σ (any axis) still called valid, > 0
  int reacquire_after_rejections = 100;         // [-] one sensor gated out this many times in a row: back to TRIAD, >= 1

  /// Every violation as "field: reason"; empty when valid.
  std::vector<std::string> validate() const;
};

struct MekfInput {
  Eigen::Vector3d w_gyro_B_rad_s = Eigen::Vector3d::Zero();   // [rad/s] mean measured rate since the last step
  Eigen::Vector3d sun_B_meas_unit = Eigen::Vector3d::Zero();  // [-] measured Sun direction, body
  bool sun_valid = false;                                     // Sun sensor sees the Sun
  Eigen::Vector3d b_B_meas_T = Eigen::Vector3d::Zero();       // [T] measured field, body
  bool b_valid = false;                                       // magnetometer sample usable
  Eigen::Quaterniond q_NB_star = Eigen::Quaterniond::Identity();  // [-] star tracker attitude, body → inertial
  bool star_valid = false;                                    // star tracker solution usable
  Eigen::Vector3d sun_N_ref_unit = Eigen::Vector3d::Zero();   // [-] onboard-model Sun direction, inertial
  Eigen::Vector3d b_N_ref_T = Eigen::Vector3d::Zero();        // [T] onboard-model field, inertial
};

/// Error state (δθ [rad], Δβ [rad/s], Δb_m [T]): attitude, gyro bias, magnetometer bias.
inline constexpr int kMekfStates = 9;
using MekfMatrix = Eigen::Matrix<double, kMekfStates, kMekfStates>;
using MekfVector = Eigen::Matrix<double, kMekfStates, 1>;

/// What one measurement did this step.
enum class MeasurementUse { kAbsent, kUsed, kRejected };

struct MekfOutput {
  Eigen::Quaterniond q_NB = Eigen::Quaterniond::Identity();     // [-] body → inertial (Hamilton)
  Eigen::Vector3d w_NB_B_rad_s = Eigen::Vector3d::Zero();       // [rad/s] gyro minus bias estimate
  Eigen::Vector3d gyro_bias_B_rad_s = Eigen::Vector3d::Zero();  // [rad/s] bias estimate
  Eigen::Vector3d magnetometer_bias_B_T = Eigen::Vector3d::Zero();  // [T] magnetometer bias estimate
  Eigen::Vector3d sun_B_est_unit = Eigen::Vector3d::Zero();     // [-] R(q)ᵀ sun_N_ref; zero until initialised
  /// Covariance of (δθ_B [rad], Δβ_B [rad/s], Δb_m,B [T]): q_true = q ⊗ exp(δθ/2),
  /// β_true = β̂ + Δβ, b_m,true = b̂_m + Δb_m.
  MekfMatrix covariance = MekfMatrix::Zero();
  bool initialized = false;  // an attitude has been acquired
  bool valid = false;        // initialised, finite, and every attitude 1σ ≤ max_attitude_sigma_rad
  MeasurementUse sun = MeasurementUse::kAbsent;
  MeasurementUse field = MeasurementUse::kAbsent;
  MeasurementUse star = MeasurementUse::kAbsent;
  std::uint64_t rejected_total = 0;  // [-] measurements refused by the gate since reset
};

/// Multiplicative extended Kalman filter for attitude and gyro bias (Lefferts, Markley & Shuster
/// 1982, "Kalman Filtering for Spacecraft Attitude Estimation", J. Guidance 5(5), §IV; Markley &
/// Crassidis 2014, Fundamentals of Spacecraft Attitude Determination and Control, §6.2;
/// Crassidis & Junkins 2012, Optimal Estimation of Dynamic Systems, 2nd ed., Table 7.1).
///
/// The reference quaternion q carries the attitude; the filter state is the body-frame error
/// rotation vector δθ (q_true = q ⊗ exp(δθ/2), Hamilton), the gyro bias error Δβ and the
/// magnetometer bias error Δb_m, reset to zero after every update. The magnetometer bias is
/// estimated as in flight attitude filters (e.g. Crassidis, Lai & Harman 2005, "Real-time
/// attitude-independent three-axis magnetometer calibration", J. Guidance 28(1), which notes
/// its observability in an attitude filter with a second vector): a constant bias would
/// otherwise be averaged into the attitude as if it were white noise. Gyro propagation follows the Farrenkopf model; Sun and field directions
/// are unit-vector measurements, the star tracker a full attitude. Each measurement passes a
/// χ² gate on its innovation first. Initialisation: the star tracker when valid, else TRIAD
/// (Sun primary, field secondary).
/// Everything the MEKF carries from one step to the next (a restart's checkpoint).
struct MekfState {
  Eigen::Quaterniond q_NB = Eigen::Quaterniond::Identity();  // [-] body to inertial, Hamilton
  Eigen::Vector3d bias_B_rad_s = Eigen::Vector3d::Zero();    // [rad/s] gyro bias estimate
  Eigen::Vector3d mag_bias_B_T = Eigen::Vector3d::Zero();    // [T] magnetometer bias estimate
  MekfMatrix P = MekfMatrix::Zero();                         // [rad², rad²/s², T²] error covariance
  bool initialized = false;                                  // [-] an attitude was acquired
  std::uint64_t rejected_total = 0;                          // [-] gated measurements so far
  std::array<int, 3> rejected_in_a_row{};                    // [-] per sensor: Sun, field, star tracker
  std::int64_t last_t_ns = 0;                                // [ns] previous step's sample time
  bool has_last_t = false;                                   // [-] last_t_ns holds one
};

class Mekf {
 public:
  using State = MekfState;
  using Params = MekfParams;
  using Input = MekfInput;
  using Output = MekfOutput;

  /// @throws std::invalid_argument listing every violation of params.validate().
  explicit Mekf(const Params& params);

  /// Back to uninitialised: identity attitude, zero biases, no previous time, no rejections.
  void reset();

  /// @param t_ns [ns] sample time; the difference to the previous call is the propagation step.
  Output step(const Input& in, std::int64_t t_ns);

  const Params& params() const { return params_; }
  /// [-] χ² gate of a two-dimensional (direction) and three-dimensional (star tracker) innovation.
  double gate2() const { return gate2_; }
  double gate3() const { return gate3_; }

  State state() const {
    return {q_NB_, bias_B_rad_s_, mag_bias_B_T_, P_, initialized_, rejected_total_, rejected_in_a_row_,
            last_t_ns_, has_last_t_};
  }
  /// Continues from `state` (a checkpoint, taken as it is: q_NB unit, P symmetric): the
  /// next step propagates state and covariance over the time since its last_t_ns.
  void restore(const State& state);

 private:
  void propagate(const Eigen::Vector3d& w_gyro_B, double dt_s);
  bool initialize(const Input& in);
  /// field_scale [1/T]: 1/|B| when meas_B is the magnetometer's field (its bias enters), else 0.
  MeasurementUse directionUpdate(const Eigen::Vector3d& meas_B, const Eigen::Vector3d& ref_N,
                                 double sigma_rad, double field_scale);
  MeasurementUse starUpdate(const Eigen::Quaterniond& q_NB_star);
  void countRejections(const MekfOutput& out);
  /// Gates the innovation, then updates and resets; kRejected leaves the state alone.
  template <int M>
  MeasurementUse update(const Eigen::Matrix<double, M, 1>& innovation,
                        const Eigen::Matrix<double, M, kMekfStates>& H,
                        const Eigen::Matrix<double, M, M>& R, double gate);

  Params params_;
  double gate2_;
  double gate3_;
  Eigen::Quaterniond q_NB_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d bias_B_rad_s_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d mag_bias_B_T_ = Eigen::Vector3d::Zero();
  MekfMatrix P_ = MekfMatrix::Zero();
  bool initialized_ = false;
  std::uint64_t rejected_total_ = 0;
  std::array<int, 3> rejected_in_a_row_{};  // per sensor: Sun, field, star tracker
  std::int64_t last_t_ns_ = 0;
  bool has_last_t_ = false;
};

/// [-] x with P(χ²_k ≤ x) = probability for k = 2 or 3 degrees of freedom.
double chiSquareQuantile(int dof, double probability);

}  // namespace flatsat::estimator
