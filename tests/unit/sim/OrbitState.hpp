// SPDX-License-Identifier: Apache-2.0
#pragma once
// Invariants of a two-body state that the orbit propagator tests check.
#include "sim/OrbitPropagator.hpp"
#include "tests/support/TestUnits.hpp"

namespace flatsat::sim::test {

/// [m²/s²] specific orbital energy v²/2 − μ/r (vis-viva).
inline double energy(const OrbitPropagator::State& s) {
  return 0.5 * s.v_N_m_s.squaredNorm() - kMu / s.r_N_m.norm();
}
/// [m] semi-major axis a = −μ / (2 ε).
inline double semiMajorAxis(const OrbitPropagator::State& s) { return -kMu / (2.0 * energy(s)); }

}  // namespace flatsat::sim::test
