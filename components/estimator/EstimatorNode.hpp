// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <optional>
#include <string>

#include "bus/Component.hpp"
#include "bus/NodeMain.hpp"
#include "components/common/LastValid.hpp"
#include "components/estimator/AttitudeEstimator.hpp"
#include "components/estimator/Mekf.hpp"
#include "components/estimator/ReferenceModel.hpp"

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
  ReferenceModelParams reference;
};

/// Attitude estimator: gyro in, plus the Sun sensor and the magnetometer when the rig has
/// them; attitude estimate out. A sensor without valid samples (eclipse, dropout) is ridden
/// through on the others, and the health message names it.
class EstimatorNode final : public bus::Component {
 public:
  EstimatorNode(bus::Bus& bus, bus::NodeOptions options, const EstimatorNodeParams& params);

 private:
  void step(const bus::StepContext& ctx) override;

  bus::InputOf<bus::topics::kGyro>& gyro_ = addInput(bus::topics::kGyro);
  bus::InputOf<bus::topics::kSunSensor>* sun_ = nullptr;              // optional
  bus::InputOf<bus::topics::kMagnetometer>* magnetometer_ = nullptr;  // optional
  bus::WriterOf<bus::topics::kAttitudeEstimate>& estimate_ =
      addOutput(bus::topics::kAttitudeEstimate);
  LastValid<msg::GyroReading> last_gyro_;  // rides through gyro dropouts
  std::optional<AttitudeEstimator> mahony_;
  std::optional<Mekf> mekf_;
  ReferenceModel reference_;
  bool use_magnetometer_;          // the field corrects after initialisation
  bool mekf_initialized_ = false;  // the MEKF's previous step had an attitude
  std::optional<Eigen::Vector3d> previous_w_B_rad_s_;  // [rad/s] gyro rate of the previous step
};

/// components.<name>, plus the onboard orbit and field knowledge from the
/// plant sections.
EstimatorNodeParams readParams(const bus::Scenario& scenario, const bus::NodeArgs& args,
                               bus::ConfigProblems& problems);

}  // namespace flatsat::estimator
