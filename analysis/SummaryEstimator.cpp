// SPDX-License-Identifier: Apache-2.0
#include "analysis/SummaryEstimator.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "bus/Convert.hpp"
#include "bus/Serialization.hpp"
#include "bus/Topics.hpp"
#include "sim/Attitude.hpp"
#include "analysis/Conventions.hpp"

namespace flatsat::analysis {

namespace {

// χ²_3 at 0.025 and 0.975 (Abramowitz & Stegun 1964, Table 26.8).
constexpr double kNees3Low = 0.2158;
constexpr double kNees3High = 9.3484;
constexpr double kFullSun = 0.999;  // [-] illumination counted as sunlight (no penumbra)

}  // namespace

void EstimatorFigures::addTruth(std::uint64_t step, const TruthSample& truth) {
  pairs_.addReference(step, {bus::quat(truth.q_inertial_body()).normalized(), truth.illumination()},
                      [this](std::uint64_t, const TruthAt& t, const EstimateAt& e) { judge(t, e); });
}

void EstimatorFigures::addEstimate(std::uint64_t step, const EstimateSample& e) {
  if (!e.has_covariance()) return;
  has_covariance_ = true;
  if (step >= last_step_) {
    last_step_ = step;
    rejected_ = e.measurements_rejected();
  }
  const double t_s = static_cast<double>(e.header().sim_time_ns()) * 1e-9;
  if (!e.valid() || t_s < acquisition_s_) return;
  const EstimateAt estimate{bus::quat(e.q_inertial_body()).normalized(),
                            Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
                                e.attitude_cov_body_rad2().data())};
  pairs_.addSample(step, estimate, [this](std::uint64_t, const TruthAt& t, const EstimateAt& est) { judge(t, est); });
}

void EstimatorFigures::judge(const TruthAt& truth, const EstimateAt& estimate) {
  // δθ with q_true = q_est ⊗ exp(δθ/2), the covariance's definition.
  const Eigen::Vector3d dtheta = sim::rotationVectorFromQuat(estimate.q_NB.conjugate() * truth.q_NB);
  const double nees = dtheta.dot(estimate.P.ldlt().solve(dtheta));
  ++counted_;
  if (nees >= kNees3Low && nees <= kNees3High) ++in_bounds_;
  if (truth.illumination >= kFullSun) {
    sunlit_sum_sq_ += dtheta.squaredNorm();
    ++sunlit_;
  }
}

void EstimatorFigures::summarize(nlohmann::ordered_json& summary) const {
  if (!has_covariance_) return;
  summary["attitude_error_deg_3sigma"] =
      sunlit_ ? 3.0 * std::sqrt(sunlit_sum_sq_ / static_cast<double>(sunlit_)) * kRadToDeg : 0.0;
  summary["nees_in_bounds_fraction"] =
      counted_ ? static_cast<double>(in_bounds_) / static_cast<double>(counted_) : 0.0;
  summary["estimator_measurements_rejected"] = rejected_;
}

}  // namespace flatsat::analysis
