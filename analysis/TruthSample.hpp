// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <type_traits>

#include "bus/Topics.hpp"

namespace flatsat::analysis {

/// A recorded sample of the dynamics server's truth (flatsat/truth).
using TruthSample = std::remove_cvref_t<decltype(bus::topics::kTruth)>::Type;
/// A recorded attitude estimate (flatsat/attitude_estimate).
using EstimateSample = std::remove_cvref_t<decltype(bus::topics::kAttitudeEstimate)>::Type;
/// A recorded field estimate (flatsat/field_estimate, seed S0).
using FieldSample = std::remove_cvref_t<decltype(bus::topics::kFieldEstimate)>::Type;
/// A recorded flap command (flatsat/flap_cmd, seed S2).
using FlapCmdSample = std::remove_cvref_t<decltype(bus::topics::kFlapCmd)>::Type;
/// A recorded thruster command (flatsat/thruster_cmd, seeds S1 and S3).
using ThrusterCmdSample = std::remove_cvref_t<decltype(bus::topics::kThrusterCmd)>::Type;

}  // namespace flatsat::analysis
