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

template <const auto& Topic>
using DefOf = std::remove_cvref_t<decltype(Topic)>;

}  // namespace

void EstimatorFigures::addTruth(std::uint64_t step, const TruthSample& truth) {
  truth_[step] = {bus::quat(truth.q_inertial_body()).normalized(), truth.illumination()};
}

void EstimatorFigures::summarize(const bus::Recording& recording, nlohmann::ordered_json& summary) const {
  bool has_covariance = false;
  double sunlit_sum_sq = 0.0;
  std::uint64_t sunlit = 0, counted = 0, in_bounds = 0, rejected = 0;
  recording.forEach(
      std::string(bus::topics::kAttitudeEstimate.name),
      [&](std::uint64_t step, const std::string&, const std::vector<std::uint8_t>& bytes) {
        const auto e = bus::deserialize<DefOf<bus::topics::kAttitudeEstimate>>(bytes);
        if (!e.has_covariance()) return;
        has_covariance = true;
        rejected = e.measurements_rejected();
        const auto it = truth_.find(step);
        const double t_s = static_cast<double>(e.header().sim_time_ns()) * 1e-9;
        if (!e.valid() || it == truth_.end() || t_s < scenario_.acquisition_s) return;
        // δθ with q_true = q_est ⊗ exp(δθ/2), the covariance's definition.
        const Eigen::Vector3d dtheta = sim::rotationVectorFromQuat(
            bus::quat(e.q_inertial_body()).normalized().conjugate() * it->second.q_NB);
        const Eigen::Matrix3d P = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
            e.attitude_cov_body_rad2().data());
        const double nees = dtheta.dot(P.ldlt().solve(dtheta));
        ++counted;
        if (nees >= kNees3Low && nees <= kNees3High) ++in_bounds;
        if (it->second.illumination >= kFullSun) {
          sunlit_sum_sq += dtheta.squaredNorm();
          ++sunlit;
        }
      });
  if (!has_covariance) return;
  summary["attitude_error_deg_3sigma"] =
      sunlit ? 3.0 * std::sqrt(sunlit_sum_sq / static_cast<double>(sunlit)) * kRadToDeg : 0.0;
  summary["nees_in_bounds_fraction"] =
      counted ? static_cast<double>(in_bounds) / static_cast<double>(counted) : 0.0;
  summary["estimator_measurements_rejected"] = rejected;
}

}  // namespace flatsat::analysis
