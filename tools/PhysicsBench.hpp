// SPDX-License-Identifier: Apache-2.0
#pragma once

namespace flatsat::tools {

/// Prints the physics figures of `flatsat bench` as key=value lines (wall time on
/// this machine, best of several batches; the project's targets in brackets):
///   igrf13_field_us   one IGRF-14 degree-13 field evaluation at one point [< 2 µs]
///   dynamics_step_us  one DynamicsModel::step of the default scenario's plant with
///                     every orbit force switched on, averaged over 2000 s of flight
///                     (so the orbit's grid steps are included) [< 20 µs]
/// Data and the scenario come from the source tree, else the installed copies;
/// a missing file prints key=nan and an error on stderr.
void printPhysicsBench();

}  // namespace flatsat::tools
