// SPDX-License-Identifier: Apache-2.0
#pragma once

#include "bus/Params.hpp"

namespace flatsat::onboard {

/// [s] `reference_field_node_s` of a component's section: how far apart the
/// nodes of its onboard field model and Sun ephemeris are (ReferenceModel.hpp),
/// 0..10, default 1; 0: evaluated at every step.
double readFieldNodeSpacing(bus::ParamReader& reader);

}  // namespace flatsat::onboard
