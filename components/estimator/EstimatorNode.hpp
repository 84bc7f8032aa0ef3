// SPDX-License-Identifier: Apache-2.0
#pragma once
#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/LastValid.hpp"
#include "components/estimator/AttitudeEstimator.hpp"
#include "components/estimator/ReferenceModel.hpp"

namespace flatsat::estimator {

struct EstimatorNodeParams {
  AttitudeEstimatorParams filter;
  ReferenceModelParams reference;
};

/// Attitude estimator: gyro, Sun sensor and (when the rig has one)
/// magnetometer in, attitude estimate out.
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
};

/// components.<name>, plus the onboard orbit and field knowledge from the
/// plant sections.
EstimatorNodeParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                               bus::ConfigProblems& problems);

}  // namespace flatsat::estimator
