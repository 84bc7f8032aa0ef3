// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "analysis/StepPairs.hpp"
#include "analysis/TruthSample.hpp"

namespace flatsat::analysis {

/// The estimator's accuracy and consistency against the recorded truth, from
/// the acquisition time on, when the estimator publishes a covariance (MEKF):
/// - attitude_error_deg_3sigma: 3·RMS of the attitude error angle in full sunlight;
/// - nees_in_bounds_fraction: share of valid estimates whose attitude NEES δθᵀP⁻¹δθ lies in
///   the two-sided 95 % bounds of χ²_3, [0.2158, 9.3484];
/// - estimator_measurements_rejected: the innovation gate's count at the end.
/// Accumulated sample by sample (analysis/RunFigures.hpp), each estimate
/// judged against the truth of its step as the later of the two comes.
class EstimatorFigures {
 public:
  explicit EstimatorFigures(double acquisition_s) : acquisition_s_(acquisition_s) {}
  void addTruth(std::uint64_t step, const TruthSample& truth);
  void addEstimate(std::uint64_t step, const EstimateSample& estimate);
  void summarize(nlohmann::ordered_json& summary) const;

 private:
  struct TruthAt {
    Eigen::Quaterniond q_NB;
    double illumination;
  };
  struct EstimateAt {
    Eigen::Quaterniond q_NB;
    Eigen::Matrix3d P;
  };
  void judge(const TruthAt& truth, const EstimateAt& estimate);
  double acquisition_s_;
  StepPairs<TruthAt, EstimateAt> pairs_;
  bool has_covariance_ = false;
  std::uint64_t last_step_ = 0;  // of the last estimate with a covariance
  double sunlit_sum_sq_ = 0.0;
  std::uint64_t sunlit_ = 0, counted_ = 0, in_bounds_ = 0, rejected_ = 0;
};

}  // namespace flatsat::analysis
