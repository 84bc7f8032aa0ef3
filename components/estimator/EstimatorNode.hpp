// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>
#include <string>

#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/LastValid.hpp"
#include "components/estimator/AttitudeEstimator.hpp"
#include "components/estimator/Mekf.hpp"
#include "components/common/onboard/ReferenceModel.hpp"
#include "vehicle/VehicleDescription.hpp"
#include "components/estimator/FieldFromMomentumEstimator.hpp"

namespace flatsat::estimator {

/// Which filter the node runs.
enum class EstimatorMethod {
  kMahony,  // TRIAD + explicit complementary filter (AttitudeEstimator), no covariance
  kMekf,    // multiplicative EKF (Mekf), publishes its covariance
};

struct EstimatorNodeParams {
  EstimatorMethod method = EstimatorMethod::kMahony;  // [-] mahony | mekf
  AttitudeEstimatorParams filter;                     // kMahony; its use_magnetometer for both
  MekfParams mekf;                                    // used by kMekf
  onboard::ReferenceModelParams reference;
  std::optional<FieldFromMomentumParams> s0;  // seed S0 field estimate (components.<name>.s0.enabled)
  double jd_epoch_utc = 0.0;            // [d] for the ecliptic of date
};

/// Attitude estimator: gyro in, plus the Sun sensor and the magnetometer when the rig has
/// them; attitude estimate out. A sensor without valid samples (eclipse, dropout) is ridden
/// through on the others, and the health message names it. With S0 on, it also asks the
/// unloading controller for coil windows and publishes the field estimate from the wheel
/// momentum (seed S0, no magnetometer needed).
class EstimatorNode final : public bus::Component {
 public:
  EstimatorNode(bus::Bus& bus, bus::NodeOptions options, const EstimatorNodeParams& params);

 private:
  void step(const bus::StepContext& ctx) override;
  /// The filter's estimate, biases, covariance (MEKF) and clock, so a restarted estimator
  /// goes on from its last step instead of acquiring again with zero bias. The S0 field
  /// estimate is not kept: it is measured again at the next coil window.
  nlohmann::json saveState() const override;
  void restoreState(const nlohmann::json& state) override;

  bus::InputOf<bus::topics::kGyro>& gyro_ = addInput(bus::topics::kGyro);
  bus::InputOf<bus::topics::kSunSensor>* sun_ = nullptr;              // optional
  bus::InputOf<bus::topics::kMagnetometer>* magnetometer_ = nullptr;  // optional
  bus::InputOf<bus::topics::kStarTracker>* star_tracker_ = nullptr;   // optional, MEKF only
  bus::WriterOf<bus::topics::kAttitudeEstimate>& estimate_ =
      addOutput(bus::topics::kAttitudeEstimate);
  LastValid<msg::GyroReading> last_gyro_;  // rides through gyro dropouts
  std::optional<AttitudeEstimator> mahony_;
  std::optional<Mekf> mekf_;
  onboard::ReferenceModel reference_;
  bool use_magnetometer_;          // the field corrects after initialisation
  bool mekf_initialized_ = false;  // the MEKF's previous step had an attitude
  bool star_valid_ = false;        // the star tracker's sample of this step was usable
  std::optional<unsigned> status_bits_;  // the sensor states the last status text told
  std::optional<Eigen::Vector3d> previous_w_B_rad_s_;  // [rad/s] gyro rate of the previous step

  void stepFieldFromMomentum(const bus::StepContext& ctx, const msg::GyroReading& gyro, const Eigen::Vector3d& sun_B_unit,
              bool sun_valid, const onboard::ReferenceVectors& reference);
  std::optional<FieldFromMomentumEstimator> s0_;
  double jd_epoch_utc_;
  bus::InputOf<bus::topics::kWheelTach>* tach_ = nullptr;           // S0
  bus::InputOf<bus::topics::kCoilWindow>* coil_window_ = nullptr;   // S0, feedback
  // Published in every rig (not asked, not valid without S0), so the topic set
  // does not depend on the estimator's configuration.
  bus::WriterOf<bus::topics::kCoilRequest>& coil_request_ = addOutput(bus::topics::kCoilRequest);
  bus::WriterOf<bus::topics::kFieldEstimate>& field_estimate_ = addOutput(bus::topics::kFieldEstimate);
};

/// The estimator's section, over the vehicle's onboard view.
EstimatorNodeParams readParams(const bus::Scenario& scenario, const vehicle::Vehicle& vehicle,
                               const bus::NodeArgs& args, bus::ConfigProblems& problems);

}  // namespace flatsat::estimator
