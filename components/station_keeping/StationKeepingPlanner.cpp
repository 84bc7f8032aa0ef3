// SPDX-License-Identifier: Apache-2.0
#include "components/station_keeping/StationKeepingPlanner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/Constants.hpp"

namespace flatsat::station_keeping {

namespace {

using Effect5 = Eigen::Matrix<double, 5, 1>;
using sim::kPi;

const double kSyncRadius_m = std::cbrt(sim::kMuEarth_m3_s2 / std::pow(sim::kEarthRotationRate_rad_s, 2));

constexpr double kShiftStep_rad = 2.5 * kPi / 180.0;

/// The change of (i, e, drift) as one vector in shares of the station box:
/// a drift by the longitude it makes over drift_horizon_s.
Effect5 scaled(const Eigen::Vector2d& di, const Eigen::Vector2d& de, double ddrift, const StationKeepingParams& p) {
  Effect5 out;
  out << di / p.box_inclination_rad, de / p.box_eccentricity, ddrift * p.drift_horizon_s / p.box_longitude_rad;
  return out;
}

bool facesInclination(const Firing& f) {
  const bool at_node = std::abs(std::remainder(f.ra_rad - 0.5 * kPi, kPi)) < 1e-9;  // 90° or 270°
  return at_node && f.job != Job::kDriftAndEccentricity;
}

/// Non-negative least squares min |B x − y|, x ≥ 0, exactly: the best of the
/// unconstrained solutions over every subset of columns whose solution is
/// non-negative (at most 2⁶ subsets here).
Eigen::VectorXd nonNegativeLeastSquares(const Eigen::Matrix<double, 5, Eigen::Dynamic>& B, const Effect5& y) {
  const int m = static_cast<int>(B.cols());
  Eigen::VectorXd best = Eigen::VectorXd::Zero(m);
  double best_residual = y.squaredNorm();
  for (unsigned subset = 1; subset < (1u << m); ++subset) {
    std::vector<int> columns;
    for (int j = 0; j < m; ++j) {
      if (subset & (1u << j)) columns.push_back(j);
    }
    Eigen::Matrix<double, 5, Eigen::Dynamic> Bs(5, columns.size());
    for (std::size_t k = 0; k < columns.size(); ++k) Bs.col(static_cast<Eigen::Index>(k)) = B.col(columns[k]);
    const auto qr = Bs.colPivHouseholderQr();
    if (qr.rank() < static_cast<Eigen::Index>(columns.size())) continue;
    const Eigen::VectorXd xs = qr.solve(y);
    if ((xs.array() < 0.0).any()) continue;
    const double residual = (Bs * xs - y).squaredNorm();
    if (residual < best_residual - 1e-18) {
      best_residual = residual;
      best.setZero();
      for (std::size_t k = 0; k < columns.size(); ++k) best(columns[k]) = xs(static_cast<Eigen::Index>(k));
    }
  }
  return best;
}

}  // namespace

std::vector<std::string> validate(const StationKeepingParams& p) {
  std::vector<std::string> problems;
  const auto check = [&](bool ok, const std::string& what) {
    if (!ok) problems.push_back(what);
  };
  check(std::abs(p.station_longitude_rad) <= kPi, "station_longitude_rad: outside [-pi, pi]");
  check(p.longitude_return_s >= 86400.0 && p.longitude_return_s <= 60 * 86400.0,
        "longitude_return_s: outside [86400, 5184000] s");
  for (const auto& problem : validate(p.thrusters)) problems.push_back("thrusters." + problem);
  check(p.thrust_N > 0.0 && p.thrust_N <= 2.0, "thrust_N: outside (0, 2] N");
  check(p.mass_kg > 0.0 && p.mass_kg <= 1e5, "mass_kg: outside (0, 1e5] kg");
  check(p.max_burn_s >= 60.0 && p.max_burn_s <= 43200.0, "max_burn_s: outside [60, 43200] s");
  check(p.max_ra_shift_rad >= 0.0 && p.max_ra_shift_rad <= 0.25 * kPi, "max_ra_shift_rad: outside [0, pi/4] rad");
  check(p.dump_arc_rad >= 0.0 && p.dump_arc_rad <= kPi / 6.0, "dump_arc_rad: outside [0, pi/6] rad");
  check(p.box_longitude_rad > 0.0 && p.box_longitude_rad <= 0.0175, "box_longitude_rad: outside (0, 0.0175] rad");
  check(p.box_inclination_rad > 0.0 && p.box_inclination_rad <= 0.0175,
        "box_inclination_rad: outside (0, 0.0175] rad");
  check(p.box_eccentricity > 0.0 && p.box_eccentricity <= 0.01, "box_eccentricity: outside (0, 0.01]");
  check(p.drift_horizon_s >= 86400.0 && p.drift_horizon_s <= 60 * 86400.0,
        "drift_horizon_s: outside [86400, 5184000] s");
  return problems;
}

StationKeepingPlanner::StationKeepingPlanner(const StationKeepingParams& params) : params_(params) {
  const auto problems = validate(params);
  if (!problems.empty()) {
    std::string text = "station keeping parameters:";
    for (const auto& problem : problems) text += " " + problem + ";";
    throw std::invalid_argument(text);
  }
}

StationKeepingPlan StationKeepingPlanner::step(const StationKeepingInputs& in) const {
  const double v = std::sqrt(sim::kMuEarth_m3_s2 / kSyncRadius_m), n = sim::kEarthRotationRate_rad_s;
  StationKeepingPlan plan;
  // A day of the Sun's declination at the equinox (0.4°) and some more.
  plan.season = seasonOf(in.sun_N_unit.normalized(), kSyncRadius_m, 0.5 * kPi / 180.0);
  std::vector<Firing> firings = firingsFor(in.failure, plan.season, std::atan2(in.sun_N_unit.y(), in.sun_N_unit.x()));

  const double lon_error = std::remainder(in.mean.longitude_rad - params_.station_longitude_rad, 2.0 * kPi);
  // The return drift before the firings' longitude jumps, which each
  // firing's own effect below adds to.
  const Effect5 wanted =
      scaled(-in.mean.i, -in.mean.e, -lon_error / params_.longitude_return_s - in.mean.drift_rad_s, params_);

  // The centres a firing is flown at: an MD firing's two halves, else one.
  const auto centres = [&](const Firing& f) {
    return dumpsMomentum(f.job) && params_.dump_arc_rad > 0.0
               ? std::vector<double>{wrapRa(f.ra_rad - params_.dump_arc_rad), wrapRa(f.ra_rad + params_.dump_arc_rad)}
               : std::vector<double>{f.ra_rad};
  };
  const auto effectOf = [&](const Firing& f, double dv) {
    const std::vector<double> at = centres(f);
    ImpulseEffect e;
    for (const double ra : at) {
      const double part = dv / static_cast<double>(at.size());
      const ImpulseEffect half = impulseEffect(part * forceDirection_orbital(f.thruster, params_.thrusters), ra, v, n);
      e.i += half.i;
      e.e += half.e;
      e.drift_rad_s += half.drift_rad_s;
      e.longitude_rad += half.longitude_rad;
    }
    // A radial firing's longitude jump changes the drift the return wants.
    return std::pair{e, scaled(e.i, e.e, e.drift_rad_s + e.longitude_rad / params_.longitude_return_s, params_)};
  };
  // The sizes the least squares finds, each shared by a group of firings; the
  // dump firings are given.
  std::vector<std::vector<int>> sized;
  const bool centre_pair_tied = params_.centre_pair_equal &&
                                (in.failure == PairFailure::k20_30 || in.failure == PairFailure::k24_26);
  for (int j = 0; j < static_cast<int>(firings.size()); ++j) {
    if (firings[j].job == Job::kMomentumDump) continue;
    const bool centre = firings[j].thruster == GeoThruster::kNC || firings[j].thruster == GeoThruster::kSC;
    const auto pair = std::find_if(sized.begin(), sized.end(), [&](const std::vector<int>& group) {
      const GeoThruster t = firings[group.front()].thruster;
      return t == GeoThruster::kNC || t == GeoThruster::kSC;
    });
    if (centre_pair_tied && centre && pair != sized.end()) {
      pair->push_back(j);
    } else {
      sized.push_back({j});
    }
  }
  // The i firings move off 90°/270° by the shift that leaves the least
  // weighted error: the heading of −i alone is not it when the d/e firings
  // turn i too (the outer-pair failures). Candidates every 2.5°.
  const std::vector<Firing> at_nodes = firings;
  double best_residual = std::numeric_limits<double>::infinity();
  Eigen::VectorXd x;
  const int candidates = static_cast<int>(std::floor(params_.max_ra_shift_rad / kShiftStep_rad));
  for (int c = -candidates; c <= candidates; ++c) {
    std::vector<Firing> shifted = at_nodes;
    for (auto& f : shifted) {
      if (facesInclination(f)) f.ra_rad = wrapRa(f.ra_rad + c * kShiftStep_rad);
    }
    Effect5 rest = wanted;
    for (const auto& f : shifted) {
      if (f.job == Job::kMomentumDump) rest -= effectOf(f, in.dump_dv_m_s).second;
    }
    Eigen::Matrix<double, 5, Eigen::Dynamic> B(5, sized.size());
    for (std::size_t k = 0; k < sized.size(); ++k) {
      Effect5 column = Effect5::Zero();
      for (const int j : sized[k]) column += effectOf(shifted[j], 1.0).second;
      B.col(static_cast<Eigen::Index>(k)) = column;
    }
    const Eigen::VectorXd sizes = nonNegativeLeastSquares(B, rest);
    const double residual = (B * sizes - rest).squaredNorm();
    if (residual < best_residual - 1e-12) {  // ties keep the shift nearer the node
      best_residual = residual;
      x = sizes;
      firings = shifted;
    }
  }

  const double max_dv = params_.max_burn_s * params_.thrust_N / params_.mass_kg;
  plan.i_after = in.mean.i;
  plan.e_after = in.mean.e;
  plan.drift_after_rad_s = in.mean.drift_rad_s;
  for (int j = 0; j < static_cast<int>(firings.size()); ++j) {
    const auto at = std::find_if(sized.begin(), sized.end(), [j](const std::vector<int>& group) {
      return std::find(group.begin(), group.end(), j) != group.end();
    });
    const double dv = std::min(max_dv, at == sized.end() ? in.dump_dv_m_s : x(at - sized.begin()));
    if (dv <= 0.0) continue;
    const ImpulseEffect e = effectOf(firings[j], dv).first;
    plan.i_after += e.i;
    plan.e_after += e.e;
    plan.drift_after_rad_s += e.drift_rad_s;
    plan.longitude_jump_rad += e.longitude_rad;
    plan.dv_total_m_s += dv;
    const std::vector<double> halves = centres(firings[j]);
    const double part = dv / static_cast<double>(halves.size());
    for (const double ra : halves) {
      plan.firings.push_back({firings[j].thruster, ra, part, part * params_.mass_kg / params_.thrust_N, firings[j].job});
    }
  }
  plan.drift_target_rad_s = -(lon_error + plan.longitude_jump_rad) / params_.longitude_return_s;
  return plan;
}

}  // namespace flatsat::station_keeping
