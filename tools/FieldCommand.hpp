// SPDX-License-Identifier: Apache-2.0
#pragma once

#include <CLI/CLI.hpp>

#include "sim/SphericalHarmonicField.hpp"

namespace flatsat::tools {

/// Registers `flatsat field --model igrf14|wmm2025|dipole|spot --date YEAR.FRAC
/// --lat DEG --lon DEG [--alt-km KM]`: prints the field at a geodetic (WGS-84) point
/// as the public geomagnetic calculators do — X north, Y east, Z down, H, F [nT],
/// D, I [deg], and for igrf14 and wmm2025 their yearly change. The command runs in
/// its callback while `app` parses and leaves its status in exit_code: 0, 1 when a
/// data file is missing, 2 for an unknown model or an input out of range.
/// Data files come from bus::dataDirs() (FLATSAT_DATA_DIR, then the install's share/flatsat/data).
CLI::App* addFieldCommand(CLI::App& app, int& exit_code);

/// [µs] Mean wall time of one field.b_G_nT() over `evaluations` (> 0) points spread
/// over the globe at 500 km (for `flatsat bench`; the project's target is < 2 µs
/// for IGRF-14 at degree 13).
double fieldEvaluationMicroseconds(const sim::SphericalHarmonicField& field, int evaluations);

}  // namespace flatsat::tools
