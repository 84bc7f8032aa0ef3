// SPDX-License-Identifier: Apache-2.0
#pragma once

#include "bus/Params.hpp"
#include "components/estimator/ReferenceModel.hpp"
#include "sim/DynamicsParams.hpp"

namespace flatsat {

/// The onboard orbit and field models of a component's section:
/// `reference_field: plant | dipole`, `reference_field_node_s` (the field model's
/// node spacing, ReferenceModel.hpp) and `reference_orbit: plant | kepler`.
/// "plant" mirrors the dynamics server's models (an onboard computer carries the
/// same IGRF, and GNSS keeps its orbit); dipole and kepler are the cruder choices.
estimator::ReferenceModelParams readReferenceModel(bus::ParamReader& reader, const sim::DynamicsParams& plant);

}  // namespace flatsat
