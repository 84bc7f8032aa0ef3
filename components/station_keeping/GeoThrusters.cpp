// SPDX-License-Identifier: Apache-2.0
#include "components/station_keeping/GeoThrusters.hpp"

#include <cmath>

#include "sim/Frames.hpp"

namespace flatsat::station_keeping {

GeoThruster partnerOf(GeoThruster thruster) {
  // Opposed corners share a power unit: the numbers add up to 50.
  return static_cast<GeoThruster>(50 - static_cast<int>(thruster));
}

PairFailure failureOf(GeoThruster thruster) {
  switch (thruster) {
    case GeoThruster::kNW:
    case GeoThruster::kSE:
      return PairFailure::k20_30;
    case GeoThruster::kNC:
    case GeoThruster::kSC:
      return PairFailure::k22_28;
    case GeoThruster::kNE:
    case GeoThruster::kSW:
      return PairFailure::k24_26;
  }
  return PairFailure::kNone;
}

bool available(GeoThruster thruster, PairFailure failure) {
  return failure == PairFailure::kNone || failureOf(thruster) != failure;
}

std::string nameOf(GeoThruster thruster) {
  static const char* const names[] = {"NW", "NC", "NE", "SW", "SC", "SE"};
  const int number = static_cast<int>(thruster);
  return std::string(names[(number - 20) / 2]) + "(" + std::to_string(number) + ")";
}

std::string nameOf(PairFailure failure) {
  switch (failure) {
    case PairFailure::kNone:
      return "nominal";
    case PairFailure::k22_28:
      return "22/28 failed";
    case PairFailure::k20_30:
      return "20/30 failed";
    case PairFailure::k24_26:
      return "24/26 failed";
  }
  return "?";
}

std::vector<std::string> validate(const GeoThrusterParams& params) {
  std::vector<std::string> problems;
  if (!(params.cant_rad >= 0.17 && params.cant_rad <= 1.4)) {
    problems.push_back("cant_rad: " + std::to_string(params.cant_rad) + " is outside [0.17, 1.4] rad");
  }
  if (!(params.slew_rad >= 0.0 && params.slew_rad <= 0.52)) {
    problems.push_back("slew_rad: " + std::to_string(params.slew_rad) + " is outside [0, 0.52] rad");
  }
  return problems;
}

Eigen::Vector3d forceDirection_orbital(GeoThruster thruster, const GeoThrusterParams& params) {
  const int number = static_cast<int>(thruster);
  const double north_row = number <= 24 ? 1.0 : -1.0;  // the north row pushes south
  // West corners (NW, SW) push east, east corners (NE, SE) west; the centre pair neither.
  double east = 0.0;
  if (thruster == GeoThruster::kNW || thruster == GeoThruster::kSW) east = 1.0;
  if (thruster == GeoThruster::kNE || thruster == GeoThruster::kSE) east = -1.0;
  const double alpha = east == 0.0 ? 0.0 : params.slew_rad;
  const double s = std::sin(params.cant_rad), c = std::cos(params.cant_rad);
  return {east * s * std::sin(alpha), -north_row * c, -s * std::cos(alpha)};
}

Eigen::Matrix3d R_N_orbital(const Eigen::Vector3d& r_N_m, const Eigen::Vector3d& v_N_m_s) {
  return sim::R_N_EastNorthZenith(r_N_m, v_N_m_s);
}

}  // namespace flatsat::station_keeping
