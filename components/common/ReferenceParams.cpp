// SPDX-License-Identifier: Apache-2.0
#include "components/common/ReferenceParams.hpp"

#include <algorithm>
#include <string>

namespace flatsat {

estimator::ReferenceModelParams readReferenceModel(bus::ParamReader& r, const sim::DynamicsParams& plant) {
  estimator::ReferenceModelParams p{plant.epoch, plant.orbit, {}, plant.field, std::nullopt};
  std::string field = "plant";
  r.read("reference_field", field);
  if (field == "plant") {
    if (plant.field_model == sim::FieldModel::kSphericalHarmonics) {
      auto harmonics = plant.field_harmonics;
      harmonics.degree = std::min(harmonics.degree, plant.field_degree);
      p.field_harmonics = harmonics;
    }
  } else if (field != "dipole") {
    r.problem("reference_field", "'" + field + "' is not dipole or plant");
  }
  r.read("reference_field_node_s", p.field_node_s, "s");
  if (!(p.field_node_s >= 0.0 && p.field_node_s <= 10.0)) {
    r.problem("reference_field_node_s", "must be in 0..10 s (0: the field model at every step)");
  }
  std::string orbit = "plant";
  r.read("reference_orbit", orbit);
  if (orbit == "plant") {
    p.orbit_track = plant.orbit_track;
    if (plant.atmosphere) p.orbit_track.forces.atmosphere = *plant.atmosphere;
  } else if (orbit != "kepler") {
    r.problem("reference_orbit", "'" + orbit + "' is not kepler or plant");
  }
  return p;
}

}  // namespace flatsat
