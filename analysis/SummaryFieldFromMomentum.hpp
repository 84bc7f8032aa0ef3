// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>
#include <unordered_map>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "analysis/TruthSample.hpp"

#include "bus/Recording.hpp"
#include "bus/Scenario.hpp"

namespace flatsat::analysis {

/// Seed S0's metrics, when the run recorded a field estimate: field error (% of
/// |B|) and roll error about the Sun line, RMS over the steps with a valid estimate,
/// judged against the recorded truth; windows solved and failed. The truth
/// comes from the summary's one pass over it (addTruth).
class FieldFromMomentumFigures {
 public:
  /// `jd_epoch`: [d] the vehicle's epoch, UTC Julian date.
  FieldFromMomentumFigures(const bus::Scenario& scenario, double jd_epoch, const bus::Recording& recording);
  void addTruth(std::uint64_t step, const TruthSample& truth);
  void summarize(const bus::Recording& recording, nlohmann::ordered_json& summary) const;

 private:
  struct TruthAt {
    Eigen::Vector3d b_B_T;
    double roll_rad;  // body y in the Sun-ecliptic frame
  };
  const bus::Scenario& scenario_;
  bool recorded_ = false;  // the recording holds field estimates
  double jd_epoch_ = 0.0;  // [d] the vehicle's epoch, UTC Julian date
  std::unordered_map<std::uint64_t, TruthAt> truth_;
};

}  // namespace flatsat::analysis
