// SPDX-License-Identifier: Apache-2.0
#pragma once
#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/LastValid.hpp"
#include "components/estimator/AttitudeEstimator.hpp"
#include <optional>

#include "components/estimator/ReferenceModel.hpp"
#include "components/estimator/S0Estimator.hpp"

namespace flatsat::estimator {

struct EstimatorNodeParams {
  AttitudeEstimatorParams filter;
  ReferenceModelParams reference;
  std::optional<S0EstimatorParams> s0;  // seed S0 field estimate (components.<name>.s0.enabled)
  double jd_epoch_utc = 0.0;            // [d] for the ecliptic of date
};

/// Attitude estimator: gyro, Sun sensor and (when the rig has one)
/// magnetometer in, attitude estimate out. With S0 on, it also asks the
/// unloading controller for coil windows and publishes the field estimate
/// from the wheel momentum (seed S0, no magnetometer needed).
class EstimatorNode final : public bus::Component {
 public:
  EstimatorNode(bus::Bus& bus, bus::NodeOptions options, const EstimatorNodeParams& params);

 private:
  void step(const bus::StepContext& ctx) override;

  bus::InputOf<bus::topics::kGyro>& gyro_ = addInput(bus::topics::kGyro);
  bus::InputOf<bus::topics::kSunSensor>& sun_ = addInput(bus::topics::kSunSensor);
  bus::InputOf<bus::topics::kMagnetometer>* magnetometer_ = nullptr;  // optional
  bus::WriterOf<bus::topics::kAttitudeEstimate>& estimate_ =
      addOutput(bus::topics::kAttitudeEstimate);
  LastValid<msg::GyroReading> last_gyro_;  // rides through gyro dropouts
  AttitudeEstimator filter_;
  ReferenceModel reference_;

  void stepS0(const bus::StepContext& ctx, const msg::GyroReading& gyro,
              const msg::SunSensorReading& sun, const ReferenceVectors& reference);
  std::optional<S0Estimator> s0_;
  double jd_epoch_utc_;
  bus::InputOf<bus::topics::kWheelTach>* tach_ = nullptr;           // S0
  bus::InputOf<bus::topics::kCoilWindow>* coil_window_ = nullptr;   // S0, feedback
  // Published in every rig (not asked, not valid without S0), so the topic set
  // does not depend on the estimator's configuration.
  bus::WriterOf<bus::topics::kCoilRequest>& coil_request_ = addOutput(bus::topics::kCoilRequest);
  bus::WriterOf<bus::topics::kFieldEstimate>& field_estimate_ = addOutput(bus::topics::kFieldEstimate);
};

/// components.<name>, plus the onboard orbit and field knowledge from the
/// plant sections.
EstimatorNodeParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                               bus::ConfigProblems& problems);

}  // namespace flatsat::estimator
