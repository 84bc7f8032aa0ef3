// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "analysis/StepPairs.hpp"
#include "analysis/TruthSample.hpp"

namespace flatsat::analysis {

/// Seed S0's metrics, when the run recorded a field estimate: field error (% of
/// |B|) and roll error about the Sun line, RMS over the steps with a valid estimate,
/// judged against the truth of its step as the later of the two comes
/// (analysis/RunFigures.hpp); windows solved and failed.
class FieldFromMomentumFigures {
 public:
  /// `jd_epoch`: [d] the vehicle's epoch, UTC Julian date.
  FieldFromMomentumFigures(double acquisition_s, double jd_epoch)
      : acquisition_s_(acquisition_s), jd_epoch_(jd_epoch) {}
  void addTruth(std::uint64_t step, const TruthSample& truth);
  void addField(std::uint64_t step, const FieldSample& field);
  void summarize(nlohmann::ordered_json& summary) const;

 private:
  struct TruthAt {
    Eigen::Vector3d b_B_T, sun_N;
    Eigen::Quaterniond q_NB;
    std::int64_t sim_time_ns;
  };
  struct FieldAt {
    Eigen::Vector3d b_B_T;
    double roll_rad;
  };
  void judge(const TruthAt& truth, const FieldAt& field);
  double acquisition_s_;
  double jd_epoch_;  // [d] the vehicle's epoch, UTC Julian date
  StepPairs<TruthAt, FieldAt> pairs_;
  double field2_ = 0.0, roll2_ = 0.0;
  std::uint64_t n_ = 0, cycles_ = 0, failed_ = 0, last_step_ = 0;
};

}  // namespace flatsat::analysis
