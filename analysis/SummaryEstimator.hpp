// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <unordered_map>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "analysis/TruthSample.hpp"

#include "bus/Recording.hpp"
#include "bus/Scenario.hpp"

namespace flatsat::analysis {

/// The estimator's accuracy and consistency against the recorded truth, from
/// the acquisition time on, when the estimator publishes a covariance (MEKF):
/// - attitude_error_deg_3sigma: 3·RMS of the attitude error angle in full sunlight;
/// - nees_in_bounds_fraction: share of valid estimates whose attitude NEES δθᵀP⁻¹δθ lies in
///   the two-sided 95 % bounds of χ²_3, [0.2158, 9.3484];
/// - estimator_measurements_rejected: the innovation gate's count at the end.
/// The truth comes from the summary's one pass over it (addTruth), the estimates from the recording.
class EstimatorFigures {
 public:
  explicit EstimatorFigures(const bus::Scenario& scenario) : scenario_(scenario) {}
  void addTruth(std::uint64_t step, const TruthSample& truth);
  void summarize(const bus::Recording& recording, nlohmann::ordered_json& summary) const;

 private:
  struct TruthAt {
    Eigen::Quaterniond q_NB;
    double illumination;
  };
  const bus::Scenario& scenario_;
  std::unordered_map<std::uint64_t, TruthAt> truth_;
};

}  // namespace flatsat::analysis
