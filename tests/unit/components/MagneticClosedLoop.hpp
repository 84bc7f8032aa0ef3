// SPDX-License-Identifier: Apache-2.0
#pragma once
// A 20 kg satellite with three coils on a 550 km, 98° dawn-dusk orbit, driven
// by a B-dot law straight on DynamicsModel (no DDS): the magnetic torque is the
// only torque, so the kinetic energy changes by the coils' work alone.
#include <cmath>
#include <functional>
#include <string>

#include "components/unloading_controller/Bdot.hpp"
#include "sim/DynamicsModel.hpp"
#include "sim/InitialDispersion.hpp"
#include "sim/KeplerOrbit.hpp"
#include "tests/support/ReferenceData.hpp"
#include "tests/support/TestUnits.hpp"

namespace flatsat::test {

inline sim::DynamicsParams dawnDuskSmallSat(std::uint64_t seed, double tumble_rate_rad_s) {
  sim::DynamicsParams p;
  p.epoch = sim::UtcEpoch{2026, 3, 20, 0, 0, 0.0};
  // At the March equinox the Sun is at RA 0: RAAN 90° puts the orbit normal
  // (sin i sin Ω, −sin i cos Ω, cos i) 8° from it — a dawn-dusk orbit.
  p.orbit = sim::OrbitElements{sim::kEarthEquatorialRadius_m + 550e3, 0.0, 98.0 * kDeg, 90.0 * kDeg, 0.0, 0.0};
  p.body.J_B_kg_m2 = Eigen::Vector3d(0.30, 0.35, 0.45).asDiagonal();  // z: major axis
  p.field = sim::igrfDipoleAt(kIgrfFile, sim::decimalYear(p.epoch));
  p.torquer_max_dipole_Am2 = Eigen::Vector3d::Constant(0.5);
  p.gravity_gradient = false;
  const sim::Tumble tumble = sim::dispersedTumble(seed, tumble_rate_rad_s);
  p.q0_NB = tumble.q_NB;
  p.w0_NB_B_rad_s = tumble.w_NB_B_rad_s;
  return p;
}

inline double orbitPeriod_s(const sim::DynamicsParams& p) { return sim::KeplerOrbit(p.orbit).period_s(); }

/// Runs `law` on the true field for `duration_s`, sampling and commanding every
/// period_ns (1 Hz by default), calling observe(truth, law output) after every step.
inline void runClosedLoop(const sim::DynamicsParams& p, unloading_controller::Bdot& law, double duration_s,
                          const std::function<void(const sim::Truth&, const unloading_controller::BdotOutput&)>& observe,
                          sim::SimTime period_ns = 1'000'000'000) {
  sim::DynamicsModel model(p);
  const auto steps = static_cast<std::int64_t>(duration_s * 1e9 / period_ns);
  for (std::int64_t k = 0; k < steps; ++k) {
    const sim::Truth& truth = model.truth();
    const auto out = law.step({truth.b_B_T, true}, truth.t);
    sim::ActuatorCommands cmd;
    cmd.dipole_B_Am2 = out.m_B_Am2;
    model.step(cmd, truth.t + period_ns);
    observe(model.truth(), out);
  }
}

}  // namespace flatsat::test
