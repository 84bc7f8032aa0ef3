// SPDX-License-Identifier: Apache-2.0
#include "components/common/onboard/ReferenceParams.hpp"

namespace flatsat::onboard {

double readFieldNodeSpacing(bus::ParamReader& r) {
  double field_node_s = 1.0;
  r.read("reference_field_node_s", field_node_s, "s");
  if (!(field_node_s >= 0.0 && field_node_s <= 10.0)) {
    r.problem("reference_field_node_s", "must be in 0..10 s (0: the field model at every step)");
  }
  return field_node_s;
}

}  // namespace flatsat::onboard
