// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <type_traits>

#include "bus/Topics.hpp"

namespace flatsat::analysis {

/// A recorded sample of the dynamics server's truth (flatsat/truth).
using TruthSample = std::remove_cvref_t<decltype(bus::topics::kTruth)>::Type;

}  // namespace flatsat::analysis
